#include "services/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stiction::services {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

ProgressBar::ProgressBar(std::string label, bool terminal)
    : label_(std::move(label)),
      terminal_(terminal),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {
  if (!terminal_) {
    std::fprintf(stderr, "%s: start\n", label_.c_str());
    std::fflush(stderr);
  }
}

ProgressBar::ProgressBar(std::string label)
    : ProgressBar(std::move(label), ::isatty(STDERR_FILENO) == 1) {}

bool ProgressBar::due(double fraction) {
  const auto now = std::chrono::steady_clock::now();
  if (!terminal_) {
    if (finished_) return false;
    const bool tenth = fraction * 10.0 >= next_tenth_ - 1e-9;
    if (fraction < 1.0 && !tenth && now - last_ < std::chrono::seconds(10)) return false;
    next_tenth_ = std::max(next_tenth_, static_cast<int>(std::floor(fraction * 10.0 + 1e-9)) + 1);
    last_ = now;
    return true;
  }
  if (drawn_ && fraction < 1.0 && now - last_ < std::chrono::milliseconds(100)) return false;
  last_ = now;
  return true;
}

void ProgressBar::draw(double fraction, const char* detail) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  fraction_ = fraction;
  if (!terminal_) {
    if (fraction >= 1.0) {
      std::fprintf(stderr, "%s: done in %.1f s (%s)\n", label_.c_str(), seconds_since(start_),
                   detail);
      finished_ = true;
    } else {
      std::fprintf(stderr, "%s: %3d%% after %.1f s (%s)\n", label_.c_str(),
                   static_cast<int>(fraction * 100.0), seconds_since(start_), detail);
    }
    std::fflush(stderr);
    return;
  }
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

void ProgressBar::items(int done, int total, const std::string& detail) {
  const double fraction = total > 0 ? double(done) / total : 1.0;
  if (!due(fraction)) return;
  const std::string text =
      std::to_string(done) + "/" + std::to_string(total) + (detail.empty() ? "" : ": " + detail);
  draw(fraction, text.c_str());
}

void ProgressBar::finish(const std::string& detail) {
  if (terminal_ || finished_) return;
  fraction_ = 1.0;
  draw(1.0, detail.c_str());
}

ProgressBar::~ProgressBar() {
  if (terminal_) {
    if (drawn_) {
      std::fprintf(stderr, "\r\033[K");
      std::fflush(stderr);
    }
    return;
  }
  if (!finished_) {
    std::fprintf(stderr, "%s: stopped at %d%% after %.1f s\n", label_.c_str(),
                 static_cast<int>(fraction_ * 100.0), seconds_since(start_));
    std::fflush(stderr);
  }
}

}  // namespace stiction::services
