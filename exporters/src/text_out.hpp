// text_out.hpp (internal) — fast, exact number formatting for the text formats (OBJ, pbrt).
#pragma once
#include <charconv>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace knit::impl {

// Appends numbers as the shortest text that reads back to the same double / float
// (std::to_chars round-trip guarantee), buffering and flushing to a stream in large blocks.
class TextOut {
public:
    explicit TextOut(std::ostream& out) : out_(out) { buf_.reserve(kBlock + 512); }
    ~TextOut() = default;
    TextOut(const TextOut&) = delete;
    TextOut& operator=(const TextOut&) = delete;

    TextOut& str(const char* s) {
        while (*s) buf_.push_back(*s++);
        return maybeFlush();
    }
    TextOut& str(const std::string& s) {
        buf_.append(s);
        return maybeFlush();
    }
    TextOut& ch(char c) {
        buf_.push_back(c);
        return maybeFlush();
    }
    TextOut& num(double v) { return put(v); }
    TextOut& num(float v) { return put(v); }
    TextOut& num(uint64_t v) { return put(v); }
    TextOut& num(int64_t v) { return put(v); }
    TextOut& num(uint32_t v) { return put(static_cast<uint64_t>(v)); }
    TextOut& num(int v) { return put(static_cast<int64_t>(v)); }
    void flush() {
        out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
        buf_.clear();
    }

private:
    static constexpr size_t kBlock = size_t(1) << 16;
    template <class T>
    TextOut& put(T v) {
        char tmp[64];
        const auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
        buf_.append(tmp, r.ptr);
        return maybeFlush();
    }
    TextOut& maybeFlush() {
        if (buf_.size() >= kBlock) flush();
        return *this;
    }
    std::ostream& out_;
    std::string buf_;
};

}  // namespace knit::impl
