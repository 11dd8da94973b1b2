// A one-line progress bar on stderr, redrawn in place; used only when stderr is a
// terminal (pipes and logs get no control characters).
#pragma once

#include <chrono>

namespace stiction::app {

class ProgressBar {
 public:
  explicit ProgressBar(double duration) : duration_(duration) {}
  ~ProgressBar();
  void update(double fraction);

 private:
  double duration_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace stiction::app
