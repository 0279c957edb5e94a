// stream.hpp — a job's answer as a stream of JSON lines (application/x-ndjson, chunked): the
// page reads each line as it comes (progress, intermediate states) and the last one says how it
// ended: {"type": "done", ...}, {"type": "cancelled"} or {"type": "error", "status", "error", ...}.
#pragma once
#include <functional>
#include <memory>
#include <string>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "jobs.hpp"

namespace knit::serve {

// A library message with the request field (or server flag) of each setting it names, in the
// page's words: "lower the repeats (\"repeats\")" (knit/setting_spelling.hpp).
std::string withPageFields(const std::string& message);

// Writes one line; throws JobCancelled when the client has gone (and cancels the job).
using Emit = std::function<void(const nlohmann::json& line)>;

// Answers with the lines `work` emits, run in the response's content provider (the server's
// worker thread) while `ticket` holds the job's slot. Exceptions end the stream with a line of
// their own: JobCancelled "cancelled", ChartTextError and knit::Error "error" with status 422
// (and line and column for the chart), RequestError its status, anything else 500.
void streamJob(httplib::Response& res, std::shared_ptr<JobTicket> ticket, const std::function<void(const Emit&)>& work);

}  // namespace knit::serve
