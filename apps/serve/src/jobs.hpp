// jobs.hpp — the server's long work: at most N jobs at once, and per page (session) only the
// newest: starting a job cancels the page's older one. A job checks its token between steps
// (relaxation steps, pipeline stages) and stops with JobCancelled.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace knit::serve {

class JobCancelled : public std::runtime_error {
public:
    JobCancelled() : std::runtime_error("cancelled") {}
};

// A job's cancellation flag, shared by the job and whoever may cancel it.
class CancelToken {
public:
    void cancel() { cancelled_ = true; }
    bool cancelled() const { return cancelled_; }
    void check() const {
        if (cancelled_) throw JobCancelled();
    }

private:
    std::atomic<bool> cancelled_{false};
};

class Jobs;

// A running job: holds one of the N slots and is its session's current job until destroyed.
class JobTicket {
public:
    JobTicket(Jobs& jobs, std::string session, std::shared_ptr<CancelToken> token);
    ~JobTicket();
    JobTicket(const JobTicket&) = delete;
    JobTicket& operator=(const JobTicket&) = delete;
    const CancelToken& token() const { return *token_; }
    std::shared_ptr<CancelToken> sharedToken() const { return token_; }

private:
    Jobs& jobs_;
    std::string session_;
    std::shared_ptr<CancelToken> token_;
};

class Jobs {
public:
    explicit Jobs(int maxJobs) : maxJobs_(maxJobs) {}

    // Cancels the session's current job, then waits up to `wait` for a free slot. Null when none
    // became free (the caller answers 503).
    std::unique_ptr<JobTicket> start(const std::string& session, std::chrono::milliseconds wait);
    // Cancels the session's current job; false when it had none.
    bool cancel(const std::string& session);
    // Cancels every job (server shutdown).
    void cancelAll();
    int running() const;
    int maxJobs() const { return maxJobs_; }

private:
    friend class JobTicket;
    void finish(const std::string& session, const CancelToken* token);

    const int maxJobs_;
    mutable std::mutex mutex_;
    std::condition_variable freed_;
    int running_ = 0;
    std::map<std::string, std::shared_ptr<CancelToken>> current_;  // session -> its newest job
    std::map<const CancelToken*, std::shared_ptr<CancelToken>> all_;
};

}  // namespace knit::serve
