#include "render/time_warp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace stiction::render {

double playback_speed(double t, const std::vector<double>& events, double window, double factor) {
  if (window <= 0.0 || factor <= 1.0 || events.empty()) return 1.0;
  double d = std::numeric_limits<double>::infinity();
  for (double e : events) d = std::min(d, std::abs(t - e));
  const double slow = 1.0 / factor;
  if (d <= window) return slow;
  const double ramp = 0.5 * window;
  if (d >= window + ramp) return 1.0;
  return slow + (1.0 - slow) * (d - window) / ramp;
}

std::vector<double> first_episodes(std::vector<double> events, double window, int episodes) {
  std::sort(events.begin(), events.end());
  if (episodes <= 0) return events;
  std::vector<double> kept;
  int count = 0;
  for (double e : events) {
    if (kept.empty() || e - kept.back() >= 2.0 * window) ++count;
    if (count > episodes) break;
    kept.push_back(e);
  }
  return kept;
}

std::vector<double> slowed_events(const std::vector<double>& times,
                                  const std::vector<std::string>& kinds, double window,
                                  int episodes) {
  if (episodes <= 0) return times;
  if (kinds.size() != times.size()) return first_episodes(times, window, episodes);
  std::vector<std::pair<double, std::string>> events;
  for (std::size_t i = 0; i < times.size(); ++i) events.emplace_back(times[i], kinds[i]);
  std::stable_sort(events.begin(), events.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> changes;
  std::string last;
  for (const auto& [t, kind] : events) {
    if (kind == "open" || kind == last) continue;
    changes.push_back(t);
    last = kind;
  }
  return first_episodes(changes, window, episodes);
}

std::vector<FrameTime> warped_frame_times(double start, double end, double step,
                                          const std::vector<double>& events, double window,
                                          double factor) {
  std::vector<FrameTime> frames;
  if (!(step > 0.0)) return frames;
  if (window <= 0.0 || factor <= 1.0 || events.empty()) {
    const int count = static_cast<int>(std::floor((end - start) / step + 1e-6)) + 1;
    frames.reserve(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) frames.push_back({start + step * i, 1.0});
    return frames;
  }
  double t = start;
  while (t <= end + 1e-6 * step) {
    const double speed = playback_speed(t, events, window, factor);
    frames.push_back({std::min(t, end), speed});
    t += step * speed;
  }
  return frames;
}

}  // namespace stiction::render
