// Finding the page's files and three.js (web_files.hpp).
#include "web_files.hpp"

#include <filesystem>
#include <vector>

#include "knit/error.hpp"

namespace knit::serve {
namespace {

namespace fs = std::filesystem;

std::string firstWith(const std::vector<fs::path>& candidates, const std::string& file, const std::string& what) {
    std::string tried;
    for (const fs::path& c : candidates) {
        std::error_code ec;
        if (fs::is_regular_file(c / file, ec)) return fs::weakly_canonical(c, ec).string();
        tried += (tried.empty() ? "" : ", ") + c.string();
    }
    throw Error("knit serve cannot find " + what + " (looked in " + tried + ")");
}

}  // namespace

std::string executablePath() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : exe.string();
}

WebFiles findWebFiles(const std::string& executable) {
    const fs::path bin = fs::path(executable).parent_path();
    WebFiles w;
    std::vector<fs::path> pages = {bin / ".." / "share" / "knit" / "serve"};
#ifdef KNIT_SERVE_SOURCE_WEB
    pages.emplace_back(KNIT_SERVE_SOURCE_WEB);  // the build tree: the source's page files
#endif
    w.page = firstWith(pages, "index.html", "its page files");
    std::vector<fs::path> threes = {fs::path(w.page) / "three"};
#ifdef KNIT_SERVE_BUILD_THREE
    threes.emplace_back(KNIT_SERVE_BUILD_THREE);  // the build tree: npm's three at set-up
#endif
    w.three = firstWith(threes, "build/three.module.js",
                        "three.js (run scripts/setup.sh or `cmake --build build --target three_js`)");
    return w;
}

}  // namespace knit::serve
