// measure.hpp — the `measure` command: runs the items and writes every raw number to the results
// JSON (after each item, so a long run keeps what it measured). With `base`, only the items run are
// replaced in a copy of that earlier run's results; each item records the run that measured it.
#pragma once
#include <string>

#include "common.hpp"

namespace sve {

struct MeasureOptions {
    std::string results;                       // results JSON to write
    std::string work = "speed-vs-error-work";  // scratch folder for exported files
    std::string images;                        // reference renders of item 5 (PNG); none if empty
    std::string items = "6,1,4,2,3,5";         // items to run, in order
    json meta = json::object();                // commit, date, command, ... (copied to the results)
    int garmentRepeats = 660;                  // repeats per side of the garment (item 6)
    std::string base;  // results JSON of an earlier run to update: its other items and header are kept
};

void measure(const MeasureOptions& options);

}  // namespace sve
