// viewPiecesScene: the scene a view's pieces make, for exporting them as curves (knit/scene.hpp).
#include <algorithm>

#include "knit/error.hpp"
#include "knit/scene.hpp"

namespace knit {
namespace {

// Appends the yarns of `more` to `to` (points, normals and colours; curve offsets shifted).
void appendYarns(MappedYarns& to, const MappedYarns& more) {
    to.curves.append(more.curves);
    to.normals.insert(to.normals.end(), more.normals.begin(), more.normals.end());
    to.colour.insert(to.colour.end(), more.colour.begin(), more.colour.end());
}

}  // namespace

Scene viewPiecesScene(const Scene& s, bool withPlies) {
    if (!s.detail()) throw Error("viewPiecesScene: the scene was built without a view (SceneOptions::detail)");
    const LevelPieces& pieces = s.detail()->pieces;
    SceneParts parts;
    parts.mesh = s.mesh();
    parts.normals = s.normals();
    parts.yarnRadius = s.yarnRadius();
    parts.grid = s.grid();
    parts.yarns = pieces.plies;
    appendYarns(parts.yarns, pieces.yarns);
    parts.plyOptions = s.plyOptions();
    if (withPlies) {
        std::vector<YarnSpan> spans = pieces.plySpans;
        spans.insert(spans.end(), pieces.yarnSpans.begin(), pieces.yarnSpans.end());
        std::stable_sort(spans.begin(), spans.end(),
                         [](const YarnSpan& a, const YarnSpan& b) { return a.yarn < b.yarn; });
        parts.plies = piecePlies(s.yarns(), spans, s.plyOptions());
    }
    return Scene::fromParts(std::move(parts));
}

}  // namespace knit
