// Checks that the plies of a view (ply curves cut out of yarns) are the full scene's plies point
// for point: shared by the detail tests (tests/lod) and the strain twist tests (tests/deform).
#pragma once
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>

#include "knit/plies.hpp"

namespace knit::test {

// Where `piece` (curve c) sits in `whole` (curve w, the same yarn's same ply at full detail): the
// index of whole's point equal to piece's first when every following point is equal too
// (cyclically on a closed whole); -1 otherwise.
inline long runOffset(const Polylines& whole, size_t w, const Polylines& piece, size_t c) {
    const uint32_t n = whole.size(w), k = piece.size(c);
    for (uint32_t o = 0; o < n; ++o) {
        bool same = true;
        for (uint32_t i = 0; i < k && same; ++i) {
            const uint32_t j = o + i;
            same = (j < n || whole.isClosed(w)) &&
                   whole.points[whole.begin(w) + j % n] == piece.points[piece.begin(c) + i];
        }
        if (same) return o;
    }
    return -1;
}

// Expects every curve of `cut` to be a run of the full plies' curve of the same yarn and ply;
// returns how many are shorter than that curve (cut out of a longer yarn).
inline size_t expectEveryCurveIsARunOfTheFullPly(const Plies& full, const Plies& cut) {
    std::map<std::pair<uint32_t, uint8_t>, size_t> wholeCurve;  // (yarn, ply) -> full curve
    for (size_t c = 0; c < full.curves.curveCount(); ++c) wholeCurve[{full.yarnOfCurve[c], full.plyOfCurve[c]}] = c;
    size_t partial = 0;
    for (size_t c = 0; c < cut.curves.curveCount(); ++c) {
        const size_t w = wholeCurve.at({cut.yarnOfCurve[c], cut.plyOfCurve[c]});
        EXPECT_GE(runOffset(full.curves, w, cut.curves, c), 0) << "ply curve " << c << " is not a run of the full ply";
        if (cut.curves.size(c) < full.curves.size(w)) ++partial;
    }
    return partial;
}

}  // namespace knit::test
