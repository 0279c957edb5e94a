// The memory budget: its default from the physical memory, the parser of its size, and the
// refusal message every estimate shares.
#include "knit/budget.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include <unistd.h>

#include "knit/error.hpp"

namespace knit {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

uint64_t physicalBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
}

}  // namespace

uint64_t MemoryBudget::defaultBytes() {
    const uint64_t cap = uint64_t(4) << 30;
    const uint64_t half = physicalBytes() / 2;
    return half > 0 ? std::min(cap, half) : cap;
}

MemoryBudget::MemoryBudget() : bytes_(defaultBytes()) {}

void MemoryBudget::require(double estimateBytes, const std::string& what, const std::string& option) const {
    if (estimateBytes <= double(bytes_)) return;  // NaN falls through: refused too
    throw Error("needs about " + formatGiB(estimateBytes) + " (estimate) for " + what + ", over the memory budget of " +
                formatGiB(double(bytes_)) + "; lower " + option + " or raise the memory budget");
}

std::string formatGiB(double bytes) {
    const double gib = bytes / kGiB;
    std::ostringstream s;
    if (gib >= 100 && gib < 1e15) s << std::fixed << std::setprecision(0);  // "1350 GiB", not "1.35e+03 GiB"
    else s.precision(gib >= 0.1 ? 3 : 2);
    s << gib << " GiB";
    return s.str();
}

uint64_t parseMemorySize(const std::string& text) {
    const auto bad = [&] {
        return Error("the memory budget '" + text + "': expected a size such as 8G, 512M, 64K or a number of bytes");
    };
    if (text.empty()) throw bad();
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    std::string unit(end);
    if (end == text.c_str() || !(value > 0) || !std::isfinite(value)) throw bad();
    if (unit.size() > 1 && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();  // "8GB", "8GiB" -> "8G", "8Gi"
    if (unit.size() == 2 && (unit[1] == 'i' || unit[1] == 'I')) unit.pop_back();
    double scale = 1;
    if (unit.size() == 1) {
        const std::string units = "KMGT";
        const size_t k = units.find(char(std::toupper(static_cast<unsigned char>(unit[0]))));
        if (k == std::string::npos) throw bad();
        scale = std::pow(1024.0, double(k + 1));
    } else if (!unit.empty()) {
        throw bad();
    }
    const double bytes = value * scale;
    if (!(bytes >= 1) || bytes > 1.8e19) throw bad();
    return uint64_t(bytes);
}

}  // namespace knit
