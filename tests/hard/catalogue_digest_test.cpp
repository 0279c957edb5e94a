// A fingerprint of every hard-case scene (yarns, binding, plies), for refactors that must not
// change outputs. Skipped unless KNIT_DIGEST_OUT names a file; then one line per case is written
// there: `name fnv1a-64-of-the-scene`. tools/compare-outputs.sh diffs two such files (one built
// from the old tree, one from the new).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "catalogue.hpp"

namespace knit::hard {
namespace {

struct Fnv {
    uint64_t h = 1469598103934665603ull;
    void bytes(const void* p, size_t n) {
        const auto* c = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
    }
    template <class T>
    void vec(const std::vector<T>& v) {
        const uint64_t n = v.size();
        bytes(&n, sizeof n);
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
    void curves(const Polylines& c) {
        vec(c.points);
        vec(c.offsets);
        vec(c.closed);
    }
};

TEST(CatalogueDigest, writesOneLinePerCase) {
    const char* out = std::getenv("KNIT_DIGEST_OUT");
    if (!out || !*out) GTEST_SKIP() << "set KNIT_DIGEST_OUT=FILE to write the digests";
    std::ofstream file(out);
    ASSERT_TRUE(file) << out;
    for (const std::string& name : catalogueNames()) {
        const HardCase hc = catalogueCase(name);
        std::optional<Scene> scene;
        std::string error;
        try {
            scene = buildScene(hc.pattern, hc.mesh, hc.options);
        } catch (const std::exception& e) {
            error = e.what();
        }
        Fnv f;
        if (scene) {
            f.curves(scene->yarns().curves);
            f.vec(scene->yarns().normals);
            f.curves(scene->plies().curves);
            const Binding& b = scene->binding();
            f.vec(b.face);
            f.vec(b.bary);
            f.vec(b.height);
            f.vec(b.twist);
            f.vec(b.offsets);
            f.vec(b.closed);
            const BindStats& st = scene->bindStats();
            for (size_t v :
                 {st.clampedVertices, st.cutVertices, st.boundaryVertices, st.weldedEnds, st.openEnds, st.closedLoops})
                f.bytes(&v, sizeof v);
        } else {
            f.bytes(error.data(), error.size());
        }
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
        file << name << ' ' << hex << '\n';
    }
}

}  // namespace
}  // namespace knit::hard
