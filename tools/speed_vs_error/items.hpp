// items.hpp — the speed-against-error measurements (7: run alone, see docs/views.md); each returns its raw numbers as JSON
// (the results file's "itemN" object) and logs one line per setting to stderr.
#pragma once
#include <string>

#include "common.hpp"

namespace sve {

json measurePlies();                                                       // 1: ply resampling density
json measureTubeSides(const knit::Scene& scene, const std::string& work);  // 2: tube sides
json measureDraco(const knit::Scene& scene, const std::string& work);      // 3: Draco position bits
json measureBaseMesh();                                                    // 4: base-mesh resolution
json measureRender(const std::string& imageDir);                           // 5: render modes (render_check)
json measureGarment(int repeats, const std::string& work);                 // 6: garment scale
json measureViews();  // 7: level of detail for a view against full detail (render_check)

}  // namespace sve
