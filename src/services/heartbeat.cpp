#include "services/heartbeat.hpp"

#include <cstdio>

namespace stiction::services {

Heartbeat::Heartbeat(std::string label, std::chrono::milliseconds quiet_limit)
    : label_(std::move(label)),
      quiet_limit_(quiet_limit),
      start_(std::chrono::steady_clock::now()),
      last_(start_),
      watcher_([this] { watch(); }) {}

Heartbeat::~Heartbeat() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  watcher_.join();
}

void Heartbeat::line(const std::string& text) {
  std::lock_guard lock(mutex_);
  std::fprintf(stderr, "%s: %s\n", label_.c_str(), text.c_str());
  std::fflush(stderr);
  last_ = std::chrono::steady_clock::now();
}

void Heartbeat::watch() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    const auto deadline = last_ + quiet_limit_;
    if (wake_.wait_until(lock, deadline, [this] { return stop_; })) return;
    const auto now = std::chrono::steady_clock::now();
    if (now < last_ + quiet_limit_) continue;  // a line came in meanwhile
    std::fprintf(stderr, "%s: still working after %.0f s\n", label_.c_str(),
                 std::chrono::duration<double>(now - start_).count());
    std::fflush(stderr);
    last_ = now;
  }
}

}  // namespace stiction::services
