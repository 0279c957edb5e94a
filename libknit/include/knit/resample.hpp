// knit/resample.hpp — denser, smooth centrelines: centripetal Catmull-Rom resampling.
#pragma once
#include "knit/binding.hpp"

namespace knit {

struct ResampleOptions {
    double spacing = 0.0005;  // target distance between samples (metres); original points kept
};

// Inserts points on the centripetal Catmull-Rom spline through each curve so that no segment
// is longer than `spacing`; original vertices are kept, repeated points are dropped. Surface
// normals are interpolated along (and renormalized).
MappedYarns resampleYarns(const MappedYarns& yarns, const ResampleOptions& options);

}  // namespace knit
