// cache_merge.cpp — PC2 chunks of one animation joined into one cache (knit/cache.hpp): the
// headers read and checked, the frame ranges checked to tile one range exactly once, the
// topologies compared, then the frames copied in order behind one header.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
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
    if (!cacheFormatOf(output, format) || format != CacheFormat::Pc2)
        throw Error("cannot write '" + output + "': merged point caches are PC2 (.pc2)");
    // Step 1: every header, and the same points, step and topology in each.
    std::vector<Pc2Range> c;
    c.reserve(chunks.size());
    for (const std::string& path : chunks) c.push_back(readPc2Range(path));
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
    // Step 3: one header, the frames in order, and the first chunk's topology; committed together.
    impl::checkOutputFolder(output);
    impl::AtomicFile cache(output, true), topology(topologyPathOf(output), true);
    CacheInfo info;
    info.points = result.points, info.frames = result.frames;
    info.startFrame = double(result.first), info.step = double(result.step);
    std::vector<char> header;
    impl::pc2Header(info, header);
    cache.stream().write(header.data(), std::streamsize(header.size()));
    for (const Pc2Range& r : c)
        impl::appendFile(cache.stream(), r.path, kPc2Header, uint64_t(12) * r.points * r.frames);
    const std::string firstTopology = topologyPathOf(c.front().path);
    impl::appendFile(topology.stream(), firstTopology, 0, std::filesystem::file_size(firstTopology));
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
