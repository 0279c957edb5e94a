// scene_refusals.hpp — shared by the tests of refusals (budget, search bounds): the message of a
// knit::Error and a small scene that builds in milliseconds.
#pragma once
#include <string>

#include "knit/error.hpp"
#include "knit/scene.hpp"

namespace knit::test {

// The message of the knit::Error `f` throws ("" when it does not throw).
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const knit::Error& e) {
        return e.what();
    }
    return "";
}

// The stockinette on a 4 x 4 plane, 3 x 3 repeats.
inline SceneOptions smallPlaneScene() {
    SceneOptions o;
    o.mesh = "plane";
    o.meshOptions.resU = o.meshOptions.resV = 4;
    o.placement.repeats = {3, 3};
    return o;
}

}  // namespace knit::test
