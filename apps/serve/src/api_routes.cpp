// The API's endpoints (api_routes.hpp): each handler checks its request before any work, then
// runs the work as a job (jobs.hpp) and answers, or streams its progress (stream.hpp).
#include "api_routes.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "chart_job.hpp"
#include "garment.hpp"
#include "knit/chart.hpp"
#include "knit/error.hpp"
#include "mesh_upload.hpp"
#include "point_cache_download.hpp"
#include "stream.hpp"
#include "swatch.hpp"

namespace knit::serve {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

void answer(httplib::Response& res, int status, const json& body) {
    res.status = status;
    res.set_header("Cache-Control", "no-store");
    res.set_content(body.dump(), "application/json");
}

void answerError(httplib::Response& res, int status, const std::string& message) {
    answer(res, status, {{"error", message}});
}

// A job slot for the session (its older job cancelled); throws RequestError 503 when every slot
// stays busy for ServeOptions::jobWaitMs.
std::shared_ptr<JobTicket> startJob(ServerState& state, const std::string& session) {
    std::unique_ptr<JobTicket> ticket = state.jobs.start(session, std::chrono::milliseconds(state.options.jobWaitMs));
    if (!ticket)
        throw RequestError(
            503, "busy: " + std::to_string(state.jobs.maxJobs()) + " jobs are running (knit serve --jobs); try again");
    return std::shared_ptr<JobTicket>(std::move(ticket));
}

// A "step" line every 20 iterations of the relaxation `stage`; with `swatchRepeats`, the swatch
// of the cell so far, the first after 1 s, then every 300 ms. A chart up to 4 x 4 has its preview
// sooner: an intermediate swatch drawn in software WebGL held the page's main thread for up to
// 0.66 s, which the preview that followed it waited for (docs/serve.md).
RelaxStepFn stepLines(const char* stage, const CancelToken& token, const Emit& emit,
                      const std::array<double, 2>* swatchRepeats) {
    auto nextSwatch = std::make_shared<Clock::time_point>(Clock::now() + std::chrono::milliseconds(1000));
    return [stage, &token, &emit, swatchRepeats, nextSwatch](const RelaxStep& step) {
        if (token.cancelled()) return false;
        json line = {{"type", "step"}, {"stage", stage}, {"iteration", step.iteration}, {"energy", step.energy}};
        if (swatchRepeats && Clock::now() > *nextSwatch) {
            line["swatch"] = swatchJson(step.pattern, *swatchRepeats);
            *nextSwatch = Clock::now() + std::chrono::milliseconds(300);
        }
        emit(line);
        return !token.cancelled();
    };
}

// The cell's relaxation with `options`: from memory, or relaxed now (and kept).
CellRelaxation cellRelaxation(ServerState& state, const Chart& chart, const ChartCell& cell,
                              const ChartPatternOptions& options) {
    const std::string key = relaxationKey(cell, options);
    CellRelaxation r;
    if (state.charts.find(key, r)) return r;
    r = relaxPageCell(chart, options);
    state.charts.put(key, r);
    return r;
}

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// The preview: the chart relaxed with previewOptions(), its intermediate swatches streamed, then a
// "preview" line with the relaxed swatch, the chart's design warnings and where the server's time
// went since the request came (`server_ms`: total, relax, swatch; the page's relaxedBreakdown).
void preview(ServerState& state, const Chart& chart, const CancelToken& token, const Emit& emit,
             const std::array<double, 2>& repeats, Clock::time_point requested) {
    ChartPatternOptions options = previewOptions();
    options.onStep = stepLines("preview", token, emit, &repeats);
    options.stepInterval = 20;
    const ChartCell cell = chartToCell(chart, cellOptions(options));
    const Clock::time_point relaxing = Clock::now();
    const RelaxedChart c = relaxedChart(chart, cell, cellRelaxation(state, chart, cell, options));
    token.check();
    const double relaxMs = msSince(relaxing);
    const Clock::time_point swatching = Clock::now();
    json swatch = swatchJson(c.pattern, repeats);
    const double swatchMs = msSince(swatching);
    // The chart's own warnings (floats, eyelets); the relaxation's wait for the full one.
    json warnings = json::array();
    addDesignWarnings(chart, cell, warnings);
    emit({{"type", "preview"},
          {"swatch", std::move(swatch)},
          {"stats", c.stats},
          {"warnings", warnings},
          {"server_ms",
           {{"total", std::lround(msSince(requested))},
            {"relax", std::lround(relaxMs)},
            {"swatch", std::lround(swatchMs)}}}});
}

// The relaxed chart, as `knit chart` relaxes it: from memory (by its cell, so an edit of the
// comments or colours alone is not relaxed again), or relaxed now with "step" lines. With
// `swatchRepeats` (the swatch), a preview comes first.
RelaxedChart relaxed(ServerState& state, const Chart& chart, const CancelToken& token, const Emit& emit,
                     const std::array<double, 2>* swatchRepeats, Clock::time_point requested = Clock::now()) {
    ChartPatternOptions options;
    options.onStep = stepLines("relax", token, emit, nullptr);
    options.stepInterval = 20;
    const ChartCell cell = chartToCell(chart, cellOptions(options));
    CellRelaxation r;
    if (!state.charts.find(relaxationKey(cell, options), r)) {
        if (swatchRepeats) preview(state, chart, token, emit, *swatchRepeats, requested);
        r = cellRelaxation(state, chart, cell, options);
    }
    return relaxedChart(chart, cell, r);
}

void handleInfo(const httplib::Request&, httplib::Response& res, ServerState& state) {
    json charts = json::array();
    for (const std::string& name : builtinChartNames())
        charts.push_back({{"name", name}, {"text", builtinChartText(name)}});
    const RequestLimits& l = state.options.limits;
    answer(res, 200,
           {{"charts", charts},
            {"meshes", builtinMeshNames()},
            {"jobs", state.options.jobs},
            {"running", state.jobs.running()},
            {"limits",
             {{"chart_bytes", l.maxChartBytes},
              {"chart_stitches", l.maxChartStitches},
              {"upload_bytes", state.options.maxUploadBytes},
              {"result_bytes", state.options.maxResultBytes}}}});
}

void handleSwatch(const httplib::Request& req, httplib::Response& res, ServerState& state) {
    const Clock::time_point requested = Clock::now();
    const SwatchRequest r = parseSwatchRequest(req.body, state.options.limits);
    const Chart chart = parsePageChart(r.chart, state.options.limits.maxChartStitches);
    std::shared_ptr<JobTicket> ticket = startJob(state, r.session);
    streamJob(res, ticket, [&state, r, chart, requested, token = ticket->sharedToken()](const Emit& emit) {
        const RelaxedChart c = relaxed(state, chart, *token, emit, &r.repeats, requested);
        token->check();
        emit({{"type", "done"},
              {"swatch", swatchJson(c.pattern, r.repeats)},
              {"warnings", c.warnings},
              {"stats", c.stats}});
    });
}

GarmentSettings garmentSettings(const ServerState& state, const GarmentRequest& r) {
    GarmentSettings s;
    s.repeats = r.repeats;
    s.gauge = r.gauge;
    s.view = r.view;
    s.budget = state.options.budget;
    s.maxFileBytes = state.options.maxResultBytes;
    return s;
}

void handleGarment(const httplib::Request& req, httplib::Response& res, ServerState& state) {
    const GarmentRequest r = parseGarmentRequest(req.body, state.options.limits, false);
    const Chart chart = parsePageChart(r.chart, state.options.limits.maxChartStitches);
    BaseMesh mesh = state.mesh(r.mesh);
    std::shared_ptr<JobTicket> ticket = startJob(state, r.session + "/garment");
    streamJob(res, ticket, [&state, r, chart, mesh, token = ticket->sharedToken()](const Emit& emit) {
        const RelaxedChart c = relaxed(state, chart, *token, emit, nullptr);
        const std::string path = state.temp.newFile("garment", "glb");
        json stats = writeGarmentGlb(
            c.pattern, mesh, garmentSettings(state, r), path, [&](const std::string& stage, int index, int total) {
                token->check();
                emit({{"type", "stage"}, {"stage", stage}, {"index", index}, {"total", total}});
            });
        token->check();
        const std::string id = state.addResult(path);
        stats["type"] = "done";
        stats["result"] = "/api/result/" + id;
        stats["warnings"] = c.warnings;
        emit(stats);
    });
}

void handleResult(const httplib::Request& req, httplib::Response& res, ServerState& state) {
    const std::string path = state.resultPath(req.matches[1]);
    std::string bytes;
    if (path.empty() || !readWholeFile(path, bytes))
        return answerError(res, 404, "no such result (the server keeps the last 16)");
    res.set_header("Cache-Control", "no-store");
    if (req.has_param("download")) res.set_header("Content-Disposition", "attachment; filename=\"knit-garment.glb\"");
    res.set_content(bytes, "model/gltf-binary");
}

void handleUpload(const httplib::Request& req, httplib::Response& res, ServerState& state) {
    const std::string name = req.get_param_value("name");
    BaseMesh mesh = loadUploadedMesh(req.body, name, state.temp, state.options.budget);
    const size_t vertices = mesh.positions.size(), triangles = mesh.faces.size();
    const std::string id = state.addUpload(std::move(mesh));
    answer(res, 200, {{"mesh", id}, {"name", name}, {"vertices", vertices}, {"triangles", triangles}});
}

void handleDownload(const httplib::Request& req, httplib::Response& res, ServerState& state) {
    const GarmentRequest r = parseGarmentRequest(req.body, state.options.limits, true);
    const Chart chart = parsePageChart(r.chart, state.options.limits.maxChartStitches);
    BaseMesh mesh = r.format == DownloadFormat::Pyp ? BaseMesh() : state.mesh(r.mesh);
    std::shared_ptr<JobTicket> ticket = startJob(state, r.session + "/download");
    const Emit quiet = [&](const json&) { ticket->token().check(); };
    const RelaxedChart c = relaxed(state, chart, ticket->token(), quiet, nullptr);
    std::string bytes, file, type;
    if (r.format == DownloadFormat::Pyp) {
        std::ostringstream out;
        writePyp(out, c.pattern);
        bytes = out.str(), file = "knit-chart.pyp", type = "application/octet-stream";
    } else if (r.format == DownloadFormat::Glb) {
        const std::string path = state.temp.newFile("download", "glb");
        writeGarmentGlb(c.pattern, mesh, garmentSettings(state, r), path, nullptr);
        readWholeFile(path, bytes);
        std::remove(path.c_str());
        file = "knit-garment.glb", type = "model/gltf-binary";
    } else {
        bytes = yarnPointCache(c.pattern, mesh, garmentSettings(state, r), state.temp);
        file = "knit-garment.pc2", type = "application/octet-stream";
    }
    res.set_header("Content-Disposition", "attachment; filename=\"" + file + "\"");
    res.set_header("Cache-Control", "no-store");
    res.set_content(bytes, type);
}

void handleCancel(const httplib::Request& req, httplib::Response& res, ServerState& state) {
    const std::string session = parseCancelRequest(req.body);
    int cancelled = 0;
    for (const char* suffix : {"", "/garment", "/download"}) cancelled += state.jobs.cancel(session + suffix) ? 1 : 0;
    answer(res, 200, {{"cancelled", cancelled}});
}

// Every handler's refusals become a JSON error with their status.
httplib::Server::Handler guarded(void (*handler)(const httplib::Request&, httplib::Response&, ServerState&),
                                 ServerState& state) {
    return [handler, &state](const httplib::Request& req, httplib::Response& res) {
        try {
            handler(req, res, state);
        } catch (const RequestError& e) {
            answerError(res, e.status(), e.what());
        } catch (const ChartTextError& e) {
            answer(res, 422, e.json());
        } catch (const JobCancelled&) {
            answerError(res, 409, "cancelled: the page started a newer job");
        } catch (const Error& e) {
            answerError(res, 422, withPageFields(e.what()));
        } catch (const std::exception& e) {
            answerError(res, 500, std::string("internal error: ") + e.what());
        }
    };
}

}  // namespace

void addApiRoutes(httplib::Server& http, ServerState& state) {
    http.Get("/api/info", guarded(handleInfo, state));
    http.Post("/api/swatch", guarded(handleSwatch, state));
    http.Post("/api/garment", guarded(handleGarment, state));
    http.Get(R"(/api/result/(r[0-9]{1,9}))", guarded(handleResult, state));
    http.Post("/api/mesh", guarded(handleUpload, state));
    http.Post("/api/download", guarded(handleDownload, state));
    http.Post("/api/cancel", guarded(handleCancel, state));
}

}  // namespace knit::serve
