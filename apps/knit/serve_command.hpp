// serve_command.hpp — `knit serve`: a local web page to write a chart and see it knitted in 3D
// (the server is apps/serve; docs/serve.md).
#pragma once
#include <string>

#include <CLI/CLI.hpp>

namespace knit::cli {

struct ServeCommand {
    CLI::App* command = nullptr;  // set by addServeCommand
    std::string host = "127.0.0.1";
    int port = 8080;  // 0: a free port
    int jobs = 2;
    double maxUploadMb = 32;
    double maxResultMb = 64;
    std::string maxMemory;  // the scenes' memory budget ("" = the default)
};

void addServeCommand(CLI::App& app, ServeCommand& serve);

// Serves until SIGINT / SIGTERM; prints the address. Throws knit::Error on bad options or an
// address it cannot bind.
int runServe(const ServeCommand& serve);

}  // namespace knit::cli
