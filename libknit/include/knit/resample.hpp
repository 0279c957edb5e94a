// knit/resample.hpp — denser, smooth centrelines: centripetal Catmull-Rom resampling.
#pragma once
#include <vector>

#include "knit/binding.hpp"

namespace knit {

struct ResampleOptions {
    double spacing = 0.0005;  // target distance between samples (metres); original points kept
};

// Inserts points on the centripetal Catmull-Rom spline through each curve so that no segment
// is longer than `spacing`; original vertices are kept, repeated points are dropped. Surface
// normals are interpolated along (and renormalized).
// Curve i of the result is curve i of the input (same closed flag); a curve with fewer than two
// distinct points stays a 0- or 1-point curve. `normals` may be empty (then the result has none).
// Throws knit::Error on a non-positive spacing, non-finite points/normals or a result of more
// than 2^32-1 points.
MappedYarns resampleYarns(const MappedYarns& yarns, const ResampleOptions& options);

}  // namespace knit
