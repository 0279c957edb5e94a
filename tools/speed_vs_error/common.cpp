// common.cpp — timing, machine and scene helpers of the speed-vs-error items (see common.hpp).
#include "common.hpp"

#include <fstream>

#include <sys/resource.h>
#include <unistd.h>

#include <glm/common.hpp>

#include "knit/export.hpp"
#include "knit/generator.hpp"
#include "knit/base_mesh.hpp"

namespace sve {

// ---- machine, timing ---------------------------------------------------------------------------

double seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::array<double, 3> loadAverage() {
    std::array<double, 3> l{0, 0, 0};
    std::ifstream in("/proc/loadavg");
    in >> l[0] >> l[1] >> l[2];
    return l;
}

json loadJson() {
    const auto l = loadAverage();
    return json::array({l[0], l[1], l[2]});
}

double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            const size_t c = line.find(':');
            return c == std::string::npos ? line : line.substr(c + 2);
        }
    return "unknown";
}

size_t memTotalBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);  // = MemTotal of /proc/meminfo
    return pages > 0 && pageSize > 0 ? size_t(pages) * size_t(pageSize) : 0;
}

json timingJson(const Timing& t) { return {{"best", t.best}, {"median", t.median}, {"runs", t.runs}}; }

// ---- scenes and files --------------------------------------------------------------------------

knit::Scene knitScene(int meshRes, double meshSize, dvec2 repeats, bool plies) {
    knit::ProceduralMeshOptions mo;
    mo.resU = mo.resV = meshRes;
    mo.size = meshSize;
    knit::SceneOptions so;
    so.placement.repeats = repeats;
    so.buildPlies = plies;
    return knit::buildScene(knit::generateStockinette(), knit::makeDrape(mo), so);
}

knit::Scene physicalScene(double size) { return knitScene(64, size, {0, 0}, true); }

json sceneSummary(const knit::Scene& s) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const dvec3& p : s.plies().curves.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return {{"cells", s.grid().cells.size()},
            {"yarn_vertices", s.yarns().curves.pointCount()},
            {"ply_vertices", s.plies().curves.pointCount()},
            {"ply_curves", s.plies().curves.curveCount()},
            {"yarn_radius_m", s.yarnRadius()},
            {"ply_radius_m", s.plies().plyRadius},
            {"extent_m", {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}}};
}

std::string workFile(const std::string& work, const std::string& name) { return (fs::path(work) / name).string(); }

size_t fileBytes(const std::string& path) {
    std::error_code ec;
    const auto n = fs::file_size(path, ec);
    return ec ? 0 : size_t(n);
}

void writeText(const std::string& path, const std::string& text) {
    knit::writeFileAtomically(
        path, [&](std::ostream& out) { out << text; }, true);
}

}  // namespace sve
