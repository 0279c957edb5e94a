// cache_merge.cpp — PC2 or MDD chunks of one animation joined into one cache (knit/cache.hpp):
// the headers (an MDD's frame range from its topology .obj) read and checked, the frame ranges checked to tile one range exactly once, the
// topologies compared, then the frames copied in order behind one header.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <boost/crc.hpp>

#include "io/atomic_file.hpp"
#include "knit/cache.hpp"
#include "knit/error.hpp"
#include "point_cache.hpp"

namespace knit {
namespace {

constexpr uint64_t kPc2Header = 32;

uint32_t u32(const unsigned char* b) {
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}
float f32(const unsigned char* b) {
    const uint32_t v = u32(b);
    float f;
    std::memcpy(&f, &v, 4);
    return f;
}

std::string topologyPathOf(const std::string& cache) {
    return std::filesystem::path(cache).replace_extension(".obj").string();
}

// A topology .obj's segments and point count (its `v` lines are the first frame's points, which
// differ between chunks): a CRC-32 of every other line, and the number of `v` lines.
std::pair<uint32_t, size_t> topologyKey(const std::string& obj, const std::string& chunk) {
    std::ifstream in(obj);
    if (!in) throw Error("point cache '" + chunk + "': its topology file '" + obj + "' cannot be read");
    boost::crc_32_type crc;
    size_t vertices = 0;
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) == 0) {
            ++vertices;
            continue;
        }
        if (line.rfind('#', 0) == 0) continue;
        crc.process_bytes(line.data(), line.size());
        crc.process_byte('\n');
    }
    return {crc.checksum(), vertices};
}

uint32_t u32be(const unsigned char* b) {
    return uint32_t(b[3]) | uint32_t(b[2]) << 8 | uint32_t(b[1]) << 16 | uint32_t(b[0]) << 24;
}

constexpr const char* kTopologyHeader = "libknit point cache topology: one l record per segment";

// The first line of a topology .obj (without its "# "), and the rest of the file after it.
std::string firstLine(const std::string& obj, const std::string& chunk) {
    std::ifstream in(obj);
    std::string line;
    if (!in || !std::getline(in, line) || line.rfind("# ", 0) != 0)
        throw Error("point cache '" + chunk + "': its topology file '" + obj + "' cannot be read or has no header");
    return line.substr(2);
}

// An MDD chunk: its header (frame and point counts, the size they need) and the frames and rate
// its topology .obj records (cacheTopologyHeader).
struct MddChunk {
    Pc2Range range;
    double fps = 0;
};
MddChunk readMddChunk(const std::string& path, const std::string& obj) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("point cache '" + path + "' cannot be read");
    unsigned char h[8];
    in.read(reinterpret_cast<char*>(h), 8);
    if (in.gcount() != 8) throw Error("point cache '" + path + "' is not an MDD file (shorter than its header)");
    MddChunk c;
    c.range.path = path;
    c.range.frames = u32be(h);
    c.range.points = u32be(h + 4);
    if (c.range.frames == 0 || c.range.frames > INT32_MAX || c.range.points > INT32_MAX)
        throw Error("point cache '" + path + "' is not an MDD file of frames (" + std::to_string(c.range.frames) +
                    " frames, " + std::to_string(c.range.points) + " points)");
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    const uint64_t expected = 8 + uint64_t(4) * c.range.frames + uint64_t(12) * c.range.points * c.range.frames;
    if (ec || size != expected)
        throw Error("point cache '" + path + "' has " + std::to_string(size) + " bytes, but its header (" +
                    std::to_string(c.range.points) + " points x " + std::to_string(c.range.frames) + " frames) needs " +
                    std::to_string(expected) + (size < expected ? " (truncated)" : ""));
    // "<kTopologyHeader>; MDD frames A-B step S at F fps"
    const std::string line = firstLine(obj, path), tag = std::string(kTopologyHeader) + "; MDD frames ";
    static const std::regex kRange(R"(^(-?[0-9]{1,9})-(-?[0-9]{1,9}) step ([0-9]{1,9}) at ([0-9.eE+-]{1,40}) fps$)");
    std::smatch m;
    int64_t first = 0, last = 0, step = 0;
    char* end = nullptr;
    const std::string rest = line.rfind(tag, 0) == 0 ? line.substr(tag.size()) : std::string();
    if (std::regex_match(rest, m, kRange)) {
        first = std::stoll(m[1]), last = std::stoll(m[2]), step = std::stoll(m[3]);
        const std::string rate = m[4];
        c.fps = std::strtod(rate.c_str(), &end);
        if (end != rate.c_str() + rate.size()) c.fps = 0;
    }
    if (step < 1 || last < first || !(c.fps > 0 && std::isfinite(c.fps)) || (last - first) % step != 0 ||
        (last - first) / step + 1 != int64_t(c.range.frames))
        throw Error("point cache '" + path + "': its topology file '" + obj +
                    "' does not record the MDD's frames (write the chunks with this knit's `animate`)");
    c.range.start = first;
    c.range.step = step;
    return c;
}

std::string frameSpan(int64_t a, int64_t b, int64_t step) {
    if (a == b) return "frame " + std::to_string(a);
    return "frames " + std::to_string(a) + "-" + std::to_string(b) + (step != 1 ? " step " + std::to_string(step) : "");
}

// Step 2: consecutive chunks (sorted by start) must continue each other; every gap and overlap named.
void checkTiling(const std::vector<Pc2Range>& c) {
    std::string problems;
    for (size_t i = 0; i + 1 < c.size(); ++i) {
        const Pc2Range &a = c[i], &b = c[i + 1];
        const int64_t next = a.last() + a.step;
        if (b.start > next)
            problems += "; " + frameSpan(next, b.start - a.step, a.step) + " missing (between '" + a.path + "' and '" +
                        b.path + "')";
        else if (b.start < next)
            problems += "; " + frameSpan(b.start, std::min(a.last(), b.last()), a.step) + " in both '" + a.path +
                        "' and '" + b.path + "'";
        else continue;
        if ((b.start - a.start) % a.step != 0)
            problems += " ('" + b.path + "' starts off the step of '" + a.path + "')";
    }
    if (!problems.empty())
        throw Error("the point caches do not tile one frame range exactly once: " + problems.substr(2));
}

}  // namespace

std::string cacheTopologyHeader(CacheFormat format, int64_t first, int64_t last, int64_t step, double fps) {
    if (format != CacheFormat::Mdd) return kTopologyHeader;
    char rate[40];
    std::snprintf(rate, sizeof rate, "%.17g", fps);  // read back exactly
    return std::string(kTopologyHeader) + "; MDD frames " + std::to_string(first) + "-" + std::to_string(last) +
           " step " + std::to_string(step) + " at " + rate + " fps";
}

Pc2Range readPc2Range(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("point cache '" + path + "' cannot be read");
    unsigned char h[kPc2Header];
    in.read(reinterpret_cast<char*>(h), kPc2Header);
    if (in.gcount() != std::streamsize(kPc2Header) || std::memcmp(h, "POINTCACHE2\0", 12) != 0)
        throw Error("point cache '" + path + "' is not a PC2 file (no POINTCACHE2 header)");
    if (u32(h + 12) != 1)
        throw Error("point cache '" + path + "' has PC2 version " + std::to_string(u32(h + 12)) + ", not 1");
    Pc2Range r;
    r.path = path;
    r.points = u32(h + 16);
    const float start = f32(h + 20), step = f32(h + 24);
    r.frames = u32(h + 28);
    if (!(std::fabs(start) < 16777216.0f) || start != std::floor(start) || !(step >= 1.0f && step < 16777216.0f) ||
        step != std::floor(step))
        throw Error("point cache '" + path + "': start frame " + std::to_string(start) + " and sample rate " +
                    std::to_string(step) + " are not whole frame numbers");
    r.start = int64_t(start);
    r.step = int64_t(step);
    if (r.frames == 0) throw Error("point cache '" + path + "' holds no frames");
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    const uint64_t expected = kPc2Header + uint64_t(12) * r.points * r.frames;
    if (ec || size != expected)
        throw Error("point cache '" + path + "' has " + std::to_string(size) + " bytes, but its header (" +
                    std::to_string(r.points) + " points x " + std::to_string(r.frames) + " frames) needs " +
                    std::to_string(expected) + (size < expected ? " (truncated)" : ""));
    return r;
}

CacheMergeResult mergePointCaches(const std::vector<std::string>& chunks, const std::string& output) {
    if (chunks.empty()) throw Error("no point caches to merge");
    CacheFormat format;
    if (!cacheFormatOf(output, format))
        throw Error("cannot write '" + output + "': merged point caches are PC2 (.pc2) or MDD (.mdd)");
    // Step 1: every header, and the same format, points, step (and MDD frame rate) and topology in each.
    const bool mdd = format == CacheFormat::Mdd;
    std::vector<Pc2Range> c;
    double fps = 0;
    c.reserve(chunks.size());
    for (const std::string& path : chunks) {
        CacheFormat chunkFormat;
        if (!cacheFormatOf(path, chunkFormat) || chunkFormat != format)
            throw Error("point cache '" + path + "' is not " + (mdd ? "an MDD (.mdd)" : "a PC2 (.pc2)") + " like '" +
                        output + "' (chunks merge into their own format)");
        if (!mdd) {
            c.push_back(readPc2Range(path));
            continue;
        }
        const MddChunk m = readMddChunk(path, topologyPathOf(path));
        if (!c.empty() && m.fps != fps)
            throw Error("point caches '" + c[0].path + "' and '" + path + "' differ: " + std::to_string(fps) + " and " +
                        std::to_string(m.fps) + " fps (not chunks of one animation)");
        fps = m.fps;
        c.push_back(m.range);
    }
    const auto key = topologyKey(topologyPathOf(c[0].path), c[0].path);
    for (const Pc2Range& r : c) {
        if (r.points != c[0].points || r.step != c[0].step)
            throw Error("point caches '" + c[0].path + "' and '" + r.path + "' differ: " + std::to_string(c[0].points) +
                        " and " + std::to_string(r.points) + " points, step " + std::to_string(c[0].step) + " and " +
                        std::to_string(r.step) + " (not chunks of one animation)");
        if (topologyKey(topologyPathOf(r.path), r.path) != key)
            throw Error("point caches '" + c[0].path + "' and '" + r.path + "' differ in topology ('" +
                        topologyPathOf(c[0].path) + "' and '" + topologyPathOf(r.path) + "')");
    }
    // Step 2: the ranges in order, tiling one range.
    std::stable_sort(c.begin(), c.end(), [](const Pc2Range& a, const Pc2Range& b) { return a.start < b.start; });
    checkTiling(c);
    CacheMergeResult result;
    result.first = c.front().start, result.last = c.back().last(), result.step = c[0].step;
    result.points = c[0].points;
    for (const Pc2Range& r : c) result.frames += r.frames;
    if (result.frames > INT32_MAX) throw Error("cannot write '" + output + "': more than 2^31-1 frames");
    // Step 3: one header, the frames in order, and the first chunk's topology (an MDD's range line
    // set to the merged range); committed together.
    impl::checkOutputFolder(output);
    impl::AtomicFile cache(output, true), topology(topologyPathOf(output), true);
    CacheInfo info;
    info.points = result.points, info.frames = result.frames;
    info.startFrame = double(result.first), info.step = double(result.step);
    info.fps = fps;
    std::vector<char> header;
    if (mdd) impl::mddHeader(info, header);
    else impl::pc2Header(info, header);
    cache.stream().write(header.data(), std::streamsize(header.size()));
    for (const Pc2Range& r : c)
        impl::appendFile(cache.stream(), r.path, mdd ? 8 + uint64_t(4) * r.frames : kPc2Header,
                         uint64_t(12) * r.points * r.frames);
    const std::string firstTopology = topologyPathOf(c.front().path);
    uint64_t skip = 0;
    if (mdd) {
        skip = firstLine(firstTopology, c.front().path).size() + 3;  // "# " ... "\n"
        topology.stream() << "# " << cacheTopologyHeader(format, result.first, result.last, result.step, fps) << '\n';
    }
    impl::appendFile(topology.stream(), firstTopology, skip, std::filesystem::file_size(firstTopology) - skip);
    topology.close();
    cache.close();
    topology.commit();
    try {
        cache.commit();
    } catch (...) {
        topology.undoCommit();
        throw;
    }
    return result;
}

}  // namespace knit
