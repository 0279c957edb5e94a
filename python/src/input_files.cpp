// Same file: device and inode (std::filesystem::equivalent), so "./p.pyp", "sub/../p.pyp" and a
// hard link or symlink to it all count.
#include "input_files.hpp"

#include <filesystem>
#include <system_error>

#include "knit/error.hpp"

namespace knitpy {

void refuseWritingOverInputs(const std::string& keyword, const std::string& path,
                             const std::vector<std::pair<std::string, std::string>>& inputs) {
    namespace fs = std::filesystem;
    for (const auto& [what, input] : inputs) {
        std::error_code ec;
        if (input.empty() || !fs::is_regular_file(input, ec) || !fs::exists(path, ec)) continue;
        if (fs::equivalent(path, input, ec) && !ec)
            throw knit::Error(keyword + " '" + path + "' is " + what + " ('" + input +
                              "'): writing there would replace it; choose another " + keyword);
    }
}

}  // namespace knitpy
