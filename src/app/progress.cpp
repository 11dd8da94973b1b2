#include "app/progress.hpp"

#include <cstdio>

namespace stiction::app {

void ProgressBar::update(double fraction) {
  const auto now = std::chrono::steady_clock::now();
  // Redraw at most ten times a second: a terminal write costs more than many steps.
  if (drawn_ && fraction < 1.0 && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth + 0.5);
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
  bar[kWidth] = '\0';
  std::fprintf(stderr, "\r[%s] %3d%%  t = %.3f s", bar, static_cast<int>(fraction * 100.0 + 0.5),
               fraction * duration_);
  std::fflush(stderr);
  drawn_ = true;
}

ProgressBar::~ProgressBar() {
  if (drawn_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }
}

}  // namespace stiction::app
