// measure.hpp — the `measure` command: runs the items and writes every raw number to the results
// JSON (after each item, so a long run keeps what it measured).
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
};

void measure(const MeasureOptions& options);

}  // namespace sve
