// animated_glb.hpp — `knit animate -o out.glb`: the frames as one GLB with a morph target per
// frame (knit/morph_gltf.hpp), refused up front when its estimated size is over the budget.
#pragma once
#include <memory>

#include "frame_sink.hpp"
#include "knit/budget.hpp"
#include "knit/export.hpp"

namespace knit::cli {

struct AnimatedGlbOptions {
    double fps = 24;      // frame k at k / fps seconds
    bool linear = false;  // LINEAR blend between frames instead of STEP
};

// True when -o asks for one animated .glb (a .glb path without a printf frame pattern).
bool isAnimatedGlb(const std::string& path, bool hasFramePattern);

// Refuses options an animated .glb cannot honour (Draco, quantization, meshopt).
void checkAnimatedGlbOptions(const ExportOptions& options);

// The sink; throws knit::Error before any frame is evaluated when the file's estimated size
// (frames x vertices x 12 bytes + ...) is over `budget`, naming the estimate and what to change.
std::unique_ptr<FrameSink> makeAnimatedGlbSink(const Animator& animator, size_t frames, const ExportOptions& options,
                                               const AnimatedGlbOptions& glb, const MemoryBudget& budget);

}  // namespace knit::cli
