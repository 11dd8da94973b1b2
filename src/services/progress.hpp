// Progress on stderr. On a terminal: a one-line bar redrawn in place, cleared when done.
// Otherwise (a pipe, a CI log): plain lines without control characters, one at the start,
// one whenever another 10% is done or 10 s have passed since the last line, and one at the
// end, so a log shows that a long job is alive and how far it got.
#pragma once

#include <chrono>
#include <string>

namespace stiction::services {

class ProgressBar {
 public:
  // `label` is printed before the bar ("simulate", "render"). `terminal`: draw a bar;
  // otherwise write plain lines (the start line at once).
  ProgressBar(std::string label, bool terminal);
  // Decides by whether stderr is a terminal.
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Simulation: fraction of the run done and the simulated time reached.
  void simulation(double fraction, double duration);
  // Rendering: frames done of frame_count, frames per second so far, seconds left.
  void frames(int done, int frame_count, double frames_per_second, double eta_seconds);
  // Any other job: `done` of `total` items, with a short description of the last one.
  void items(int done, int total, const std::string& detail);
  // The job is over: plain lines get their end line ("done in 3.2 s (DETAIL)"). Without it
  // the destructor reports where the job stopped.
  void finish(const std::string& detail);

 private:
  // False while the last redraw is under 100 ms old (a terminal write costs more than
  // many steps), except for the final update; for plain lines, false until the next 10%
  // or 10 s.
  bool due(double fraction);
  void draw(double fraction, const char* detail);

  std::string label_;
  bool terminal_ = false;
  bool drawn_ = false;
  bool finished_ = false;
  double fraction_ = 0.0;
  int next_tenth_ = 1;  // plain lines: the next multiple of 10% that earns a line
  std::chrono::steady_clock::time_point start_{}, last_{};
};

}  // namespace stiction::services
