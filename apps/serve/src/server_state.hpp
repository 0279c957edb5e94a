// server_state.hpp — what the API's handlers share: options, temporary folder, jobs, relaxed
// charts, uploaded meshes and finished results (both by server-made ids, never by paths).
#pragma once
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "chart_job.hpp"
#include "jobs.hpp"
#include "knit/base_mesh.hpp"
#include "server.hpp"
#include "temp_folder.hpp"

namespace knit::serve {

class ServerState {
public:
    explicit ServerState(const ServeOptions& o) : options(o), jobs(o.jobs) {}

    const ServeOptions options;
    TempFolder temp;
    Jobs jobs;
    RelaxedCharts charts;

    // Uploaded meshes: the newest kMaxUploads are kept ("upload-N").
    std::string addUpload(BaseMesh mesh);
    // A built-in mesh by name or an upload by id; throws RequestError 404 for neither.
    BaseMesh mesh(const std::string& nameOrId) const;

    // Finished files (garment GLBs) in the temporary folder: the newest kMaxResults are kept
    // ("r<N>", the older files are deleted).
    std::string addResult(const std::string& path);
    // The path of a result id; "" when there is none.
    std::string resultPath(const std::string& id) const;

    static constexpr size_t kMaxUploads = 8, kMaxResults = 16;

private:
    mutable std::mutex mutex_;
    unsigned nextUpload_ = 1, nextResult_ = 1;
    std::deque<std::pair<std::string, BaseMesh>> uploads_;
    std::deque<std::pair<std::string, std::string>> results_;
};

}  // namespace knit::serve
