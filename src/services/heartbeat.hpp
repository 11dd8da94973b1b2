// For jobs made of items whose lengths are unknown (the runs of a study): prints the lines
// it is given and, from a watcher thread, "LABEL: still working after N s" whenever 10 s
// pass without a line, so a CI log never goes quiet for long.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace stiction::services {

class Heartbeat {
 public:
  explicit Heartbeat(std::string label,
                     std::chrono::milliseconds quiet_limit = std::chrono::seconds(10));
  ~Heartbeat();
  Heartbeat(const Heartbeat&) = delete;
  Heartbeat& operator=(const Heartbeat&) = delete;

  // Prints "LABEL: LINE" on stderr (thread-safe) and restarts the quiet clock.
  void line(const std::string& text);

 private:
  void watch();

  std::string label_;
  std::chrono::milliseconds quiet_limit_;
  std::chrono::steady_clock::time_point start_, last_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread watcher_;
};

}  // namespace stiction::services
