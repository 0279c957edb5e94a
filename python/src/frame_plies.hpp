// python/src/frame_plies.hpp — plies of a new pose with the rest pose's point layout, for
// animation caches and Blender meshes whose vertex count must not change from frame to frame.
#pragma once
#include "knit/plies.hpp"

namespace knitpy {

// The plies of `yarns` (the scene's yarns evaluated on a new pose) with `options`, laid out
// exactly like `rest` (same curves, offsets, point counts): each yarn's resampled centreline is
// re-sampled uniformly by arc length to the rest count when its own count differs (the yarn
// stretched), then swept as makePlies sweeps it. Where the counts agree (e.g. at rest) the result
// is makePlies' bit for bit. Parallel over yarns.
knit::Plies pliesWithRestLayout(const knit::MappedYarns& yarns, const knit::PlyOptions& options,
                                const knit::Plies& rest);

}  // namespace knitpy
