// The job slots and the newest job per session (jobs.hpp).
#include "jobs.hpp"

namespace knit::serve {

JobTicket::JobTicket(Jobs& jobs, std::string session, std::shared_ptr<CancelToken> token)
    : jobs_(jobs), session_(std::move(session)), token_(std::move(token)) {}

JobTicket::~JobTicket() { jobs_.finish(session_, token_.get()); }

std::unique_ptr<JobTicket> Jobs::start(const std::string& session, std::chrono::milliseconds wait) {
    auto token = std::make_shared<CancelToken>();
    std::unique_lock<std::mutex> lock(mutex_);
    // The page moved on: its older job stops at its next check and frees its slot.
    auto it = current_.find(session);
    if (it != current_.end()) it->second->cancel();
    current_[session] = token;
    freed_.notify_all();  // an older job of this page still waiting for a slot gives up
    const bool got = freed_.wait_for(lock, wait, [&] { return running_ < maxJobs_ || token->cancelled(); });
    if (!got || token->cancelled()) {
        auto now = current_.find(session);
        if (now != current_.end() && now->second == token) current_.erase(now);
        return nullptr;
    }
    ++running_;
    all_[token.get()] = token;
    return std::make_unique<JobTicket>(*this, session, token);
}

bool Jobs::cancel(const std::string& session) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = current_.find(session);
    if (it == current_.end()) return false;
    it->second->cancel();
    current_.erase(it);
    freed_.notify_all();
    return true;
}

void Jobs::cancelAll() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& entry : all_) entry.second->cancel();
    for (auto& entry : current_) entry.second->cancel();
    freed_.notify_all();
}

int Jobs::running() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return running_;
}

void Jobs::finish(const std::string& session, const CancelToken* token) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        --running_;
        all_.erase(token);
        auto it = current_.find(session);
        if (it != current_.end() && it->second.get() == token) current_.erase(it);
    }
    freed_.notify_all();
}

}  // namespace knit::serve
