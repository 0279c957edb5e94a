// `knit cache merge`: chunks -> one PC2 or MDD and its topology (knit/cache.hpp mergePointCaches).
#include "cache_command.hpp"

#include <cstdio>
#include <filesystem>

#include "knit/cache.hpp"
#include "path_collisions.hpp"

namespace knit::cli {

void addCacheCommand(CLI::App& app, CacheCommand& c) {
    c.command = app.add_subcommand("cache", "Point cache tools (merge the chunks of a farm bake)");
    c.command->require_subcommand(1);
    c.merge = c.command->add_subcommand(
        "merge", "Join PC2 or MDD chunks (any order) into one cache: they must tile one frame range exactly once and "
                 "share the topology (each chunk's .obj beside it; an MDD's records its frames)");
    c.merge->add_option("chunks", c.chunks, "The PC2 or MDD chunks (e.g. chunk_*.pc2)")->required();
    c.merge->add_option("-o,--output", c.output, "The merged .pc2 or .mdd (its topology .obj is written beside it)")
        ->required();
}

int runCache(const CacheCommand& c) {
    std::vector<NamedPath> inputs;
    for (const std::string& chunk : c.chunks) {
        inputs.push_back({"chunk", chunk});
        inputs.push_back({"the topology of a chunk", std::filesystem::path(chunk).replace_extension(".obj").string()});
    }
    // The topology beside -o only for a cache name (-o m.obj was its own topology: a garbled refusal).
    CacheFormat format;
    const bool cache = cacheFormatOf(c.output, format);
    refuseCollidingPaths(inputs, {{"-o", c.output},
                                  {"the topology file of -o",
                                   cache ? std::filesystem::path(c.output).replace_extension(".obj").string() : ""}});
    const CacheMergeResult r = mergePointCaches(c.chunks, c.output);
    std::printf("merged %zu chunks: frames %lld-%lld (step %lld, %zu frames, %zu points) into %s\n", c.chunks.size(),
                static_cast<long long>(r.first), static_cast<long long>(r.last), static_cast<long long>(r.step),
                r.frames, r.points, c.output.c_str());
    return 0;
}

}  // namespace knit::cli
