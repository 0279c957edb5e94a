// server.hpp — `knit serve`: the page's HTTP server (cpp-httplib). Static files (the page and
// three.js) and the JSON API of docs/serve.md; long work in at most `jobs` jobs at once, a
// page's newer job cancelling its older one; every file it writes lives in its own temporary
// folder, removed when the Server is destroyed.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "api_request.hpp"
#include "knit/budget.hpp"
#include "web_files.hpp"

namespace knit::serve {

struct ServeOptions {
    std::string host = "127.0.0.1";
    int port = 8080;       // 0: any free port (bind() returns it)
    int jobs = 2;          // jobs (relaxations, garment builds, downloads) at once
    int jobWaitMs = 2000;  // how long a request waits for a free job slot before 503
    uint64_t maxUploadBytes = uint64_t(32) << 20;
    uint64_t maxResultBytes = uint64_t(64) << 20;  // a garment GLB, estimated before it is written
    MemoryBudget budget;                           // each job's scene
    RequestLimits limits;
    WebFiles web;
};

class Server {
public:
    // Creates the temporary folder and the routes; throws knit::Error for bad options.
    explicit Server(const ServeOptions& options);
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    // Binds host:port; returns the port (the free one for port 0). Throws knit::Error when the
    // address cannot be bound.
    int bind();
    // Serves until stop() (call bind() first).
    void run();
    // Cancels the running jobs and makes run() return; callable from any thread.
    void stop();
    const std::string& tempFolder() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace knit::serve
