// util/platform.cpp — /proc readers and file-name helpers (see platform.hpp).
#include "util/platform.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace knit::util {

namespace {

// The value in kB of a "Name:   123 kB" line of /proc/self/status, in bytes; 0 if absent.
size_t statusBytes(const char* field) {
    std::ifstream status("/proc/self/status");
    const std::string prefix = std::string(field) + ":";
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind(prefix, 0) == 0) {
            std::istringstream in(line.substr(prefix.size()));
            size_t kb = 0;
            in >> kb;
            return kb * 1024;
        }
    }
    return 0;
}

}  // namespace

size_t peakResidentBytes() { return statusBytes("VmHWM"); }

size_t residentBytes() { return statusBytes("VmRSS"); }

size_t anonymousResidentBytes() { return statusBytes("RssAnon"); }

bool resetPeakResident() {
    std::ofstream clear("/proc/self/clear_refs");
    if (!clear) return false;
    clear << "5";
    clear.flush();
    return bool(clear);
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace knit::util
