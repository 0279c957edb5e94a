// FNV-1a 64 of a byte string: the key of on-disk cache entries (charts, strain tables).
#pragma once
#include <cstdint>
#include <string>

namespace knit::util {

inline uint64_t fnv1a(const std::string& s) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

}  // namespace knit::util
