// Uses the installed headers of knit::knit and knit::exporters: builds a small scene and
// exports its plies; prints the counts and exits 0 when they are non-zero.
#include <cstdio>
#include <string>

#include "knit/error.hpp"
#include "knit/export.hpp"
#include "knit/scene.hpp"

int main(int argc, char** argv) {
    const std::string out = argc > 1 ? argv[1] : "consumer-plies.obj";
    try {
        knit::SceneOptions options;
        options.mesh = "plane";
        options.placement.repeats = {3.0, 3.0};
        const knit::Scene scene = knit::buildScene(options);
        knit::ExportOptions exportOptions;
        exportOptions.path = out;
        const knit::ExportStats stats = knit::exportScene(scene, exportOptions);
        std::printf("consumer: %zu yarn points, %zu ply points, %zu bytes to %s\n", scene.yarns().curves.pointCount(),
                    scene.plies().curves.pointCount(), stats.bytes, out.c_str());
        return scene.plies().curves.pointCount() > 0 && stats.bytes > 0 ? 0 : 1;
    } catch (const knit::Error& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
