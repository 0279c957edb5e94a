// knit::sameFile (knit/same_file.hpp): device and inode, else the canonical paths.
#include "knit/same_file.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <system_error>

namespace knit {

bool sameFile(const std::string& a, const std::string& b) {
    namespace fs = std::filesystem;
    struct stat sa {
    }, sb{};
    const bool ea = ::stat(a.c_str(), &sa) == 0, eb = ::stat(b.c_str(), &sb) == 0;
    if (ea && eb) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    if (ea != eb) return false;
    std::error_code ec1, ec2;
    const fs::path ca = fs::weakly_canonical(fs::absolute(a), ec1), cb = fs::weakly_canonical(fs::absolute(b), ec2);
    return !ec1 && !ec2 && ca == cb;
}

}  // namespace knit
