// A one-line progress bar on stderr, redrawn in place; used only when stderr is a
// terminal (pipes and logs get no control characters). The line is cleared when the bar is
// destroyed, so whatever is printed next starts on a clean line.
#pragma once

#include <chrono>
#include <string>

namespace stiction::app {

class ProgressBar {
 public:
  // `label` is printed before the bar ("simulate", "render").
  explicit ProgressBar(std::string label) : label_(std::move(label)) {}
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Simulation: fraction of the run done and the simulated time reached.
  void simulation(double fraction, double duration);
  // Rendering: frames done of frame_count, frames per second so far, seconds left.
  void frames(int done, int frame_count, double frames_per_second, double eta_seconds);

 private:
  // False while the last redraw is under 100 ms old (a terminal write costs more than
  // many steps), except for the final update.
  bool due(double fraction);
  void draw(double fraction, const char* detail);

  std::string label_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace stiction::app
