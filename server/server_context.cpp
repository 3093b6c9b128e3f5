#include "server_context.h"

#include <algorithm>

namespace meshwave::server {

void ServerContext::Register(const std::shared_ptr<Closable>& session) {
  std::lock_guard lock(sessions_mutex_);
  // Drop dead entries now and then so the list stays about as long as the
  // number of open connections.
  if (sessions_.size() >= 64 && sessions_.size() % 64 == 0) {
    std::erase_if(sessions_, [](const auto& w) { return w.expired(); });
  }
  sessions_.push_back(session);
  if (stopping_) session->Shutdown();  // accepted while the server stops
}

void ServerContext::ShutdownSessions() {
  stopping_ = true;
  std::vector<std::shared_ptr<Closable>> live;
  {
    std::lock_guard lock(sessions_mutex_);
    for (const auto& w : sessions_) {
      if (auto s = w.lock()) live.push_back(std::move(s));
    }
    sessions_.clear();
  }
  // Outside the lock, as the style guide asks of shared state.
  for (const auto& s : live) s->Shutdown();
}

}  // namespace meshwave::server
