// The HTTP server of `knit serve` (server.hpp): static files, the API routes, request checks.
#include "server.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <csignal>

#include <httplib.h>

#include "api_routes.hpp"
#include "knit/error.hpp"
#include "server_state.hpp"

namespace knit::serve {
namespace {

// The largest JSON body: the chart text and room for the other fields.
uint64_t jsonBodyLimit(const ServeOptions& o) { return o.limits.maxChartBytes * 2 + 16384; }

bool isLoopback(const std::string& host) { return host == "127.0.0.1" || host == "localhost" || host == "::1"; }

// Requests a browser sends from the page itself: on a loopback server the Host header must name
// the loopback address (a web site that rebinds its DNS name to 127.0.0.1 cannot reach the API),
// and API posts must be JSON or a mesh upload (a form of another site cannot post them without
// the browser asking first, which this server never allows).
bool refused(const httplib::Request& req, httplib::Response& res, const ServeOptions& o, int port) {
    const std::string host = req.get_header_value("Host");
    const std::string hostName = host.substr(0, host.rfind(':') == std::string::npos ? host.size() : host.rfind(':'));
    if (isLoopback(o.host) && !host.empty() && !isLoopback(hostName) && hostName != "[::1]") {
        res.status = 421;
        res.set_content(R"({"error":"this server answers only to 127.0.0.1 / localhost"})", "application/json");
        return true;
    }
    if (req.method == "POST") {
        const std::string type = req.get_header_value("Content-Type");
        const bool upload = req.path == "/api/mesh";
        // Sizes from the Content-Length header, before the body is read.
        const uint64_t length = req.get_header_value<uint64_t>("Content-Length");
        const uint64_t limit = upload ? o.maxUploadBytes : jsonBodyLimit(o);
        if (length > limit) {
            res.status = 413;
            res.set_content(nlohmann::json{{"error", std::string(upload ? "the upload" : "the request body") + " is " +
                                                         std::to_string(length) + " bytes, over the limit of " +
                                                         std::to_string(limit)}}
                                .dump(),
                            "application/json");
            return true;
        }
        if ((upload && type.rfind("application/octet-stream", 0) != 0) ||
            (!upload && type.rfind("application/json", 0) != 0)) {
            res.status = 415;
            res.set_content(std::string(R"({"error":"send the body as )") +
                                (upload ? "application/octet-stream" : "application/json") + R"("})",
                            "application/json");
            return true;
        }
    }
    (void)port;
    return false;
}

}  // namespace

struct Server::Impl {
    explicit Impl(const ServeOptions& o) : state(o) {}
    ServerState state;
    httplib::Server http;
    int port = 0;
    std::atomic<bool> inRun{false}, stopRequested{false};
};

Server::Server(const ServeOptions& options) {
    if (options.jobs < 1 || options.jobs > 64) throw Error("the number of jobs must be from 1 to 64");
    // A client that goes away mid-answer must not kill the server: writes then fail with EPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    impl_ = std::make_unique<Impl>(options);
    httplib::Server& http = impl_->http;
    // Threads for connections: the jobs, plus the page's static files and short requests.
    const size_t threads = size_t(options.jobs) + 12;
    http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
    http.set_payload_max_length(std::max<uint64_t>(options.maxUploadBytes, jsonBodyLimit(options)));
    http.set_keep_alive_timeout(2);
    http.set_read_timeout(10);
    http.set_write_timeout(10);
    http.set_mount_point("/three", options.web.three);
    http.set_mount_point("/", options.web.page);
    // A JavaScript type cpp-httplib does not compress: it would brotli-compress three.js's 1.3 MB
    // on every load (seconds of CPU) for a loopback connection.
    http.set_file_extension_and_mimetype_mapping("js", "application/x-javascript");
    http.set_file_extension_and_mimetype_mapping("mjs", "application/x-javascript");
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        return refused(req, res, impl_->state.options, impl_->port) ? httplib::Server::HandlerResponse::Handled
                                                                    : httplib::Server::HandlerResponse::Unhandled;
    });
    http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
        if (res.body.empty()) {
            const std::string message = res.status == 413   ? "the request body is over the size limit"
                                        : res.status == 404 ? "not found"
                                                            : "bad request";
            res.set_content(nlohmann::json{{"error", message}}.dump(), "application/json");
        }
    });
    addApiRoutes(http, impl_->state);
}

Server::~Server() { stop(); }

int Server::bind() {
    const ServeOptions& o = impl_->state.options;
    const int port =
        o.port == 0 ? impl_->http.bind_to_any_port(o.host) : (impl_->http.bind_to_port(o.host, o.port) ? o.port : -1);
    if (port <= 0)
        throw Error("cannot listen on " + o.host + ":" + std::to_string(o.port) +
                    " (in use, or not an address of this machine)");
    impl_->port = port;
    return port;
}

void Server::run() {
    impl_->inRun = true;
    if (!impl_->stopRequested) impl_->http.listen_after_bind();
    impl_->inRun = false;
}

void Server::stop() {
    if (!impl_) return;
    impl_->stopRequested = true;
    impl_->state.jobs.cancelAll();
    // run() may be about to listen (a stop before it does would be lost): wait until it listens.
    for (int k = 0; k < 400 && impl_->inRun && !impl_->http.is_running(); ++k)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    impl_->http.stop();
}

const std::string& Server::tempFolder() const { return impl_->state.temp.path(); }

}  // namespace knit::serve
