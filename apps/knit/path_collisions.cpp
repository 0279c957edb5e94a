// Output paths checked against the inputs and each other (see path_collisions.hpp).
#include "path_collisions.hpp"

#include <filesystem>

#include "knit/error.hpp"
#include "knit/file_kind.hpp"
#include "knit/same_file.hpp"
#include "util/platform.hpp"

namespace knit::cli {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse(const NamedPath& out, const NamedPath& other) {
    throw Error(out.role + " '" + out.path + "' and " + other.role + " '" + other.path +
                "' name the same file; choose another " + out.role + " path");
}

}  // namespace

void refuseOtherFormatName(const std::string& flag, const std::string& path, const std::string& kind,
                           const std::string& ext) {
    const std::string named = fileKind(path);
    if (named.empty() || named.rfind(kind, 0) == 0) return;
    throw Error(flag + " '" + path + "': this command writes " + kind + " (" + ext + "), but the name is that of " +
                named + "; choose a " + ext + " name");
}

void refuseCollidingPaths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
    for (size_t i = 0; i < outputs.size(); ++i) {
        if (outputs[i].path.empty()) continue;
        for (const NamedPath& in : inputs)
            if (!in.path.empty() && fs::exists(in.path) && sameFile(outputs[i].path, in.path)) refuse(outputs[i], in);
        for (size_t j = 0; j < i; ++j)
            if (!outputs[j].path.empty() && sameFile(outputs[i].path, outputs[j].path)) refuse(outputs[i], outputs[j]);
    }
}

std::string gltfBufferOf(const std::string& output) {
    if (util::lowerExtension(output) != "gltf") return "";
    const fs::path p(output);
    return (p.parent_path() / (p.stem().string() + ".bin")).string();
}

}  // namespace knit::cli
