// frame_sink.hpp — where `knit animate` sends its evaluated frames: a point cache with its
// topology, one file per frame, or one animated .glb.
#pragma once
#include "knit/animation.hpp"
#include "knit/base_mesh.hpp"

namespace knit::cli {

class FrameSink {
public:
    virtual ~FrameSink() = default;
    virtual void write(int number, const BaseMesh& mesh, const AnimationFrame& frame) = 0;
    virtual void commit() = 0;
};

}  // namespace knit::cli
