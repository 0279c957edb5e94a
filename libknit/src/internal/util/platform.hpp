// util/platform.hpp — what the operating system tells about this process, and file names (internal).
#pragma once
#include <cstddef>
#include <string>

namespace knit::util {

// Peak resident memory of this process (VmHWM of /proc/self/status) in bytes; 0 if unavailable.
size_t peakResidentBytes();
// Current resident memory (VmRSS) in bytes; 0 if unavailable.
size_t residentBytes();
// The part of it that is anonymous memory (RssAnon: allocated, not mapped files' pages).
size_t anonymousResidentBytes();
// Resets the peak to the current resident size (Linux >= 4.0, /proc/self/clear_refs);
// false if the kernel refused.
bool resetPeakResident();

// The extension of `path`'s file name, lower case, without the dot ("GLB" -> "glb"; "" if none).
std::string lowerExtension(const std::string& path);

}  // namespace knit::util
