// cache_writer.cpp — PointCacheWriter: header, frames streamed through a temporary file, rename
// on commit; and the segment OBJ of the cache topology.
#include <cmath>
#include <string>

#include "formats.hpp"
#include "io/atomic_file.hpp"
#include "knit/cache.hpp"
#include "knit/error.hpp"
#include "point_cache.hpp"
#include "text_out.hpp"

namespace knit {

bool cacheFormatOf(const std::string& path, CacheFormat& format) {
    const impl::Format* f = impl::formatOf(path);
    if (!f || !f->pointCache) return false;
    format = std::string(f->extension) == "mdd" ? CacheFormat::Mdd : CacheFormat::Pc2;
    return true;
}

struct PointCacheWriter::State {
    explicit State(const std::string& path) : file(path, true) {}
    impl::AtomicFile file;
    CacheFormat format = CacheFormat::Pc2;
    CacheInfo info;
    size_t written = 0;
    std::vector<char> bytes;  // one frame's encoding, reused
};

PointCacheWriter::PointCacheWriter(const std::string& path, const CacheInfo& info) {
    // Step 1: the format and the counts the header can hold.
    CacheFormat format;
    if (!cacheFormatOf(path, format))
        throw Error("cannot write point cache '" + path + "': the extension must be .pc2 or .mdd");
    if (info.points > INT32_MAX || info.frames > INT32_MAX)
        throw Error("cannot write point cache '" + path + "': more than 2^31-1 points or frames");
    if (format == CacheFormat::Mdd && !(info.fps > 0 && std::isfinite(info.fps)))
        throw Error("cannot write point cache '" + path + "': the frame rate must be a positive number");
    // Step 2: the temporary file and the header.
    state_ = std::make_unique<State>(path);
    state_->format = format;
    state_->info = info;
    if (format == CacheFormat::Pc2) impl::pc2Header(info, state_->bytes);
    else impl::mddHeader(info, state_->bytes);
    state_->file.stream().write(state_->bytes.data(), static_cast<std::streamsize>(state_->bytes.size()));
}

PointCacheWriter::~PointCacheWriter() = default;

void PointCacheWriter::writeFrame(const std::vector<glm::dvec3>& points) {
    State& s = *state_;
    if (points.size() != s.info.points)
        throw Error("point cache '" + s.file.path() + "': frame " + std::to_string(s.written) + " has " +
                    std::to_string(points.size()) + " points, the cache " + std::to_string(s.info.points));
    if (s.written == s.info.frames)
        throw Error("point cache '" + s.file.path() + "': more than the " + std::to_string(s.info.frames) +
                    " frames of its header");
    s.bytes.clear();
    if (s.format == CacheFormat::Pc2) impl::pc2Frame(points, s.bytes);
    else impl::mddFrame(points, s.bytes);
    s.file.stream().write(s.bytes.data(), static_cast<std::streamsize>(s.bytes.size()));
    if (!s.file.stream()) throw Error("cannot write '" + s.file.path() + "': writing failed (disk full or I/O error)");
    ++s.written;
}

void PointCacheWriter::commit() {
    State& s = *state_;
    if (s.written != s.info.frames)
        throw Error("point cache '" + s.file.path() + "': " + std::to_string(s.written) + " of " +
                    std::to_string(s.info.frames) + " frames written");
    s.file.commit();
}

const std::string& PointCacheWriter::tempPath() const { return state_->file.tempPath(); }

void writeSegmentObj(const std::string& path, const Polylines& curves, const std::string& header) {
    impl::AtomicFile file(path, false);
    {
        impl::TextOut t(file.stream());
        t.str("# ").str(header).ch('\n');
        // Step 1: the points in cache order; step 2: one `l i j` per segment (1-based).
        for (const glm::dvec3& p : curves.points) t.str("v ").num(p.x).ch(' ').num(p.y).ch(' ').num(p.z).ch('\n');
        for (size_t c = 0; c < curves.curveCount(); ++c) {
            const uint32_t b = curves.begin(c), e = curves.end(c);
            if (e - b < 2) continue;
            for (uint32_t i = b; i + 1 < e; ++i) t.str("l ").num(uint64_t(i) + 1).ch(' ').num(uint64_t(i) + 2).ch('\n');
            if (curves.isClosed(c) && e - b > 2) t.str("l ").num(uint64_t(e)).ch(' ').num(uint64_t(b) + 1).ch('\n');
        }
        t.flush();
    }
    file.commit();
}

}  // namespace knit
