// Uploads and results by id (server_state.hpp).
#include "server_state.hpp"

#include <algorithm>
#include <cstdio>

namespace knit::serve {

std::string ServerState::addUpload(BaseMesh mesh) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::string id = "upload-" + std::to_string(nextUpload_++);
    uploads_.emplace_back(id, std::move(mesh));
    while (uploads_.size() > kMaxUploads) uploads_.pop_front();
    return id;
}

BaseMesh ServerState::mesh(const std::string& nameOrId) const {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const auto& [id, m] : uploads_)
            if (id == nameOrId) return m;
    }
    const std::vector<std::string> names = builtinMeshNames();
    if (std::find(names.begin(), names.end(), nameOrId) == names.end()) {
        std::string known;
        for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
        throw RequestError(404, "\"mesh\": no built-in mesh or upload '" + nameOrId + "' (built-ins: " + known +
                                    "; uploads are kept while they are among the last " + std::to_string(kMaxUploads) +
                                    ")");
    }
    return builtinMesh(nameOrId);
}

std::string ServerState::addResult(const std::string& path) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::string id = "r" + std::to_string(nextResult_++);
    results_.emplace_back(id, path);
    while (results_.size() > kMaxResults) {
        std::remove(results_.front().second.c_str());
        results_.pop_front();
    }
    return id;
}

std::string ServerState::resultPath(const std::string& id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [rid, path] : results_)
        if (rid == id) return path;
    return "";
}

}  // namespace knit::serve
