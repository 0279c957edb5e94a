// bcc_writer.cpp — Cem Yuksel's BCC binary curves.
//
// Layout: a 64-byte header { char sign[3] = "BCC"; uint8 byteCount = 0x44 (4-byte ints and
// floats); char curveType[2] = "C0" (uniform Catmull-Rom); char dimensions = 3; char
// upDimension = 1 (y, as glTF); uint64 curveCount; uint64 totalControlPointCount; char
// fileInfo[40] }, then per curve an int32 point count (negative = closed loop: the segment
// last -> first is implied, points stored once) followed by count x 3 float32 (world space).
// Curves with fewer than 2 points are not written. Little-endian.
#include <cstring>
#include <limits>
#include <vector>

#include "io/atomic_file.hpp"
#include "formats.hpp"
#include "knit/error.hpp"

namespace knit::impl {

static_assert(sizeof(float) == 4, "BCC needs 32-bit floats");

void exportBcc(const FormatJob& job) {
    const Polylines& curves = *job.input.curves;
    // Step 1: count what is written (curves with >= 2 points).
    uint64_t curveCount = 0, pointCount = 0;
    for (size_t c = 0; c < curves.curveCount(); ++c) {
        const uint32_t n = curves.size(c);
        if (n < 2) continue;
        if (n > uint32_t(std::numeric_limits<int32_t>::max()))
            throw Error("cannot export '" + job.options.path + "': curve " + std::to_string(c) +
                        " has too many points for BCC");
        ++curveCount;
        pointCount += n;
    }
    // Step 2: header.
    AtomicFile file(job.options.path, true);
    std::ostream& out = file.stream();
    char header[64];
    std::memset(header, 0, sizeof(header));
    header[0] = 'B';
    header[1] = 'C';
    header[2] = 'C';
    header[3] = 0x44;
    header[4] = 'C';
    header[5] = '0';
    header[6] = 3;
    header[7] = 1;
    std::memcpy(header + 8, &curveCount, 8);
    std::memcpy(header + 16, &pointCount, 8);
    std::strncpy(header + 24, "libknit yarn curves", 39);
    out.write(header, 64);
    // Step 3: per curve a signed count and the float32 points.
    std::vector<float> xyz;
    for (size_t c = 0; c < curves.curveCount(); ++c) {
        const uint32_t n = curves.size(c);
        if (n < 2) continue;
        const int32_t count = curves.isClosed(c) ? -int32_t(n) : int32_t(n);
        out.write(reinterpret_cast<const char*>(&count), 4);
        xyz.resize(size_t(n) * 3);
        for (uint32_t i = 0; i < n; ++i) {
            const glm::dvec3& p = curves.points[curves.begin(c) + i];
            xyz[3 * i] = float(p.x);
            xyz[3 * i + 1] = float(p.y);
            xyz[3 * i + 2] = float(p.z);
        }
        out.write(reinterpret_cast<const char*>(xyz.data()), std::streamsize(xyz.size() * 4));
    }
    file.commit();
    job.stats.curves = curveCount;
    job.stats.vertices = pointCount;
    job.stats.chunks = 1;
    job.stats.bytes = file.bytesWritten();
}

}  // namespace knit::impl
