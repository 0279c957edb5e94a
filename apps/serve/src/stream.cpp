// Streaming a job's JSON lines (stream.hpp).
#include "stream.hpp"

#include <string>
#include <vector>

#include "api_request.hpp"
#include "chart_job.hpp"
#include "knit/error.hpp"
#include "knit/setting_spelling.hpp"

namespace knit::serve {
namespace {}  // namespace

std::string withPageFields(const std::string& message) {
    static const std::vector<SettingSpelling> fields = {
        {"the repeats", "\"repeats\""},
        {"the gauge", "\"gauge\""},
        {"the memory budget", "knit serve --max-memory"},
        {"the eye position", "\"view.eye\""},
        {"the target position", "\"view.target\""},
        {"the up direction", "\"view.up\""},
        {"the field of view", "\"view.fov\""},
        {"the image width", "\"view.width\""},
        {"the image height", "\"view.height\""},
    };
    return spellSettings(message, fields);
}

namespace {

nlohmann::json errorLine(int status, const std::string& message) {
    return {{"type", "error"}, {"status", status}, {"error", message}};
}

// The last line for how the work ended.
nlohmann::json endLine(const std::exception_ptr& failure) {
    try {
        std::rethrow_exception(failure);
    } catch (const JobCancelled&) {
        return {{"type", "cancelled"}};
    } catch (const ChartTextError& e) {
        nlohmann::json line = e.json();
        line["type"] = "error";
        line["status"] = 422;
        return line;
    } catch (const RequestError& e) {
        return errorLine(e.status(), e.what());
    } catch (const Error& e) {
        return errorLine(422, withPageFields(e.what()));
    } catch (const std::exception& e) {
        return errorLine(500, std::string("internal error: ") + e.what());
    }
}

}  // namespace

void streamJob(httplib::Response& res, std::shared_ptr<JobTicket> ticket,
               const std::function<void(const Emit&)>& work) {
    res.set_header("Cache-Control", "no-store");
    res.set_chunked_content_provider("application/x-ndjson", [ticket, work](size_t, httplib::DataSink& sink) {
        bool gone = false;
        const Emit emit = [&](const nlohmann::json& line) {
            const std::string text = line.dump() + "\n";
            if (gone || !sink.write(text.data(), text.size())) {
                gone = true;
                ticket->sharedToken()->cancel();  // the page has gone: stop the work
                throw JobCancelled();
            }
        };
        try {
            work(emit);
        } catch (...) {
            const nlohmann::json line = endLine(std::current_exception());
            if (gone) return false;
            const std::string text = line.dump() + "\n";
            if (!sink.write(text.data(), text.size())) return false;
        }
        sink.done();
        return true;
    });
}

}  // namespace knit::serve
