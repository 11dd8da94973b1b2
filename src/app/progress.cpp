#include "app/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stiction::app {

bool ProgressBar::due(double fraction) {
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && fraction < 1.0 && now - last_ < std::chrono::milliseconds(100)) return false;
  last_ = now;
  return true;
}

void ProgressBar::draw(double fraction, const char* detail) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth + 0.5);
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
  bar[kWidth] = '\0';
  // \033[K clears what a longer previous line left behind.
  std::fprintf(stderr, "\r%s [%s] %3d%%  %s\033[K", label_.c_str(), bar,
               static_cast<int>(fraction * 100.0 + 0.5), detail);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::simulation(double fraction, double duration) {
  if (!due(fraction)) return;
  char detail[64];
  std::snprintf(detail, sizeof detail, "t = %.3f s", fraction * duration);
  draw(fraction, detail);
}

void ProgressBar::frames(int done, int frame_count, double frames_per_second, double eta_seconds) {
  const double fraction = frame_count > 0 ? double(done) / frame_count : 1.0;
  if (!due(fraction)) return;
  char detail[96];
  const long eta = std::lround(std::max(0.0, eta_seconds));
  std::snprintf(detail, sizeof detail, "frame %d/%d  %.1f fps  ETA %ld:%02ld", done, frame_count,
                frames_per_second, eta / 60, eta % 60);
  draw(fraction, detail);
}

ProgressBar::~ProgressBar() {
  if (drawn_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }
}

}  // namespace stiction::app
