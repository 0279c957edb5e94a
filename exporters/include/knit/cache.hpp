// knit/cache.hpp — point caches of an animated curve set: the points of every frame streamed
// into one file that animation tools read (Blender's Mesh Cache modifier, Houdini, Maya, 3ds
// Max), with the constant topology written once beside it.
//
// Formats (by extension of the cache path):
//   .pc2  PC2, little-endian: char[12] "POINTCACHE2\0", int32 version 1, int32 points,
//         float32 start frame, float32 sample rate (frames between samples: the frame step), int32 samples,
//         then float32 x, y, z per point per sample.
//   .mdd  MDD, big-endian: int32 frames, int32 points, float32 time (seconds) per frame, then
//         float32 x, y, z per point per frame.
// The header holds the frame count, so it is given up front. The cache is written to a
// temporary sibling and renamed by commit(): an exception (or an interrupted run that unwinds)
// leaves no partial cache.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "knit/polylines.hpp"

namespace knit {

enum class CacheFormat { Pc2, Mdd };

// The cache format of `path` by extension; false when it is neither .pc2 nor .mdd.
bool cacheFormatOf(const std::string& path, CacheFormat& format);

struct CacheInfo {
    size_t points = 0;
    size_t frames = 0;
    double startFrame = 0;  // PC2: the first sample's frame number
    double step = 1;        // PC2: frames between samples (the sample rate field)
    double fps = 24;        // MDD: frame k's time is k / fps seconds
};

class PointCacheWriter {
public:
    // Opens the temporary file and writes the header. Throws knit::Error naming the path
    // (unknown extension, unwritable folder, more than 2^31-1 points or frames).
    PointCacheWriter(const std::string& path, const CacheInfo& info);
    ~PointCacheWriter();  // removes the temporary file unless committed
    PointCacheWriter(const PointCacheWriter&) = delete;
    PointCacheWriter& operator=(const PointCacheWriter&) = delete;

    // Appends one frame (exactly info.points points, as float32). Throws knit::Error on a wrong
    // count, a frame too many, or a failed write.
    void writeFrame(const std::vector<glm::dvec3>& points);
    // Renames the finished cache onto its path; throws unless every frame was written.
    void commit();
    // The temporary file (for tests of interrupted runs).
    const std::string& tempPath() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

// The frame range a PC2 file holds, from its header (frame numbers start, start + step, ...).
struct Pc2Range {
    std::string path;
    uint32_t points = 0;
    int64_t start = 0;  // first frame number
    int64_t step = 1;   // frames between samples
    uint32_t frames = 0;
    int64_t last() const { return start + step * (int64_t(frames) - 1); }
};
// Reads and checks the header of a PC2 file: the magic, version 1, integral start frame and
// step (>= 1), and a file size of exactly 32 + 12 x points x frames bytes. Throws knit::Error
// "point cache '<path>': <what is wrong>".
Pc2Range readPc2Range(const std::string& path);

// The first line (after "# ") of the topology .obj beside a point cache: for an MDD, which has no
// start frame in its header (its frame times start at 0), the frames it holds and their rate,
// "... MDD frames 51-100 step 1 at 24 fps", which knit cache merge reads back.
std::string cacheTopologyHeader(CacheFormat format, int64_t first, int64_t last, int64_t step, double fps);

// Concatenates PC2 chunks (e.g. `knit animate --first A --last B` runs on a farm) into one PC2
// at `output`, or MDD chunks into one MDD (their ranges and frame rate read from the first line
// of each chunk's .obj, cacheTopologyHeader), with its topology .obj copied from the first
// chunk's (the first frame's points, as a single run writes it; an MDD's range line set to the
// merged range). The chunks, in any order, must hold the same points and step and
// tile one contiguous frame range exactly once, each beside its topology .obj with the same
// segments; otherwise a knit::Error names the missing or doubled frames and their chunks, or the
// chunk that differs. Both outputs appear whole or not at all.
struct CacheMergeResult {
    int64_t first = 0, last = 0, step = 1;
    size_t frames = 0, points = 0;
};
CacheMergeResult mergePointCaches(const std::vector<std::string>& chunks, const std::string& output);

// The topology of a point cache as OBJ: `v` per point (of one frame) in cache order, then one
// `l i j` record per segment (closed curves: last -> first too; no point repeated), which every
// OBJ reader imports as plain edges with the vertex order kept. Written atomically.
void writeSegmentObj(const std::string& path, const Polylines& curves, const std::string& header);

}  // namespace knit
