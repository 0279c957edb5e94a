// Same file: knit::sameFile (device and inode), so "./p.pyp", "sub/../p.pyp" and a hard link or
// symlink to it all count, as on the command line.
#include "input_files.hpp"

#include <filesystem>
#include <system_error>

#include "knit/error.hpp"
#include "knit/same_file.hpp"

namespace knitpy {

void refuseWritingOverInputs(const std::string& keyword, const std::string& path,
                             const std::vector<std::pair<std::string, std::string>>& inputs) {
    namespace fs = std::filesystem;
    for (const auto& [what, input] : inputs) {
        std::error_code ec;
        if (input.empty() || !fs::is_regular_file(input, ec) || !fs::exists(path, ec)) continue;
        if (knit::sameFile(path, input))
            throw knit::Error(keyword + " '" + path + "' is " + what + " ('" + input +
                              "'): writing there would replace it; choose another " + keyword);
    }
}

}  // namespace knitpy
