// `knit serve`: flags, the address line, and a clean stop on Ctrl-C (serve_command.hpp).
#include "serve_command.hpp"

#include <pthread.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>
#include <utility>

#include "knit/budget.hpp"
#include "knit/error.hpp"
#include "server.hpp"

namespace knit::cli {

void addServeCommand(CLI::App& app, ServeCommand& s) {
    s.command = app.add_subcommand("serve", "Serve a local web page: write a chart and see it knitted in 3D");
    s.command
        ->add_option("--host", s.host, "Address to listen on (another than 127.0.0.1 exposes the page to the network)")
        ->capture_default_str();
    s.command->add_option("--port", s.port, "Port (0: a free one; the address is printed)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    s.command->add_option("--jobs", s.jobs, "Relaxations and garment builds at once")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    s.command->add_option("--max-upload-mb", s.maxUploadMb, "Largest mesh upload (MB)")
        ->check(CLI::Range(0.001, 4096.0))
        ->capture_default_str();
    s.command->add_option("--max-result-mb", s.maxResultMb, "Largest garment file the page may ask for (MB)")
        ->check(CLI::Range(0.001, 4096.0))
        ->capture_default_str();
    s.command->add_option("--max-memory", s.maxMemory,
                          "Memory budget of each job's scene (e.g. 2G; default min(4G, RAM/2))");
}

int runServe(const ServeCommand& s) {
    // An empty host listened on every address (the socket library's reading of ""), with only a warning.
    if (s.host.empty())
        throw Error("--host must name an address or host name to listen on (127.0.0.1: this machine only), got ''");
    serve::ServeOptions o;
    o.host = s.host;
    o.port = s.port;
    o.jobs = s.jobs;
    // NaN passes CLI11's range checks, and converting it to an integer is undefined (on x86 a
    // limit of 2^63 bytes: uploads of any size).
    for (const auto& [flag, mb] :
         {std::pair{"--max-upload-mb", s.maxUploadMb}, std::pair{"--max-result-mb", s.maxResultMb}})
        if (!(mb >= 0.001 && mb <= 4096.0))
            throw Error(std::string(flag) + " must be a size of 0.001 to 4096 MB, got " + std::to_string(mb));
    o.maxUploadBytes = uint64_t(s.maxUploadMb * 1048576.0);
    o.maxResultBytes = uint64_t(s.maxResultMb * 1048576.0);
    if (!s.maxMemory.empty()) o.budget = MemoryBudget(parseMemorySize(s.maxMemory));
    o.web = serve::findWebFiles(serve::executablePath());
    // SIGINT / SIGTERM go to one thread that stops the server; every other thread (the server's
    // workers included, which inherit the mask) has them blocked.
    sigset_t stopSignals;
    sigemptyset(&stopSignals);
    sigaddset(&stopSignals, SIGINT);
    sigaddset(&stopSignals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);
    serve::Server server(o);
    const int port = server.bind();
    if (s.host != "127.0.0.1" && s.host != "localhost" && s.host != "::1")
        std::fprintf(stderr,
                     "knit serve: warning: listening on %s, not only this machine: anyone who can reach it can use "
                     "the page and the server's CPU\n",
                     s.host.c_str());
    const std::string shown = s.host.find(':') != std::string::npos ? "[" + s.host + "]" : s.host;
    std::printf("knit serve: http://%s:%d/ (Ctrl-C stops it)\n", shown.c_str(), port);
    std::printf("knit serve: temporary files in %s (removed when it stops)\n", server.tempFolder().c_str());
    std::printf("knit serve: page from %s, three.js from %s\n", o.web.page.c_str(), o.web.three.c_str());
    std::fflush(stdout);
    // The waiter looks for a stop signal every 200 ms until the server has stopped.
    std::atomic<bool> stopped{false};
    std::thread waiter([&] {
        const timespec tick{0, 200 * 1000 * 1000};
        bool signalled = false;
        while (!stopped) {
            if (!signalled) signalled = sigtimedwait(&stopSignals, nullptr, &tick) > 0;
            else std::this_thread::sleep_for(std::chrono::milliseconds(50));
            // Again until run() has returned: a stop before the server listened would be lost.
            if (signalled) server.stop();
        }
    });
    server.run();
    stopped = true;
    waiter.join();
    std::printf("knit serve: stopped\n");
    return 0;
}

}  // namespace knit::cli
