#include "problems.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace stiction::peers {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The sample whose time is nearest t.
const Sample& at(const std::vector<Sample>& samples, double t) {
  const Sample* best = &samples.front();
  for (const Sample& s : samples) {
    if (std::abs(s.t - t) < std::abs(best->t - t)) best = &s;
  }
  return *best;
}

double slip(const Sample& s) { return s.v[0] - kSphere.radius * s.w[1]; }

// The slip of the sphere falls by (7/2) mu g per second while it slides. A sample counts as
// sliding while its slip exceeds half of one step's fall: an engine that sticks drops below
// that within the step that crosses zero. The stick time is where the line through the last
// two sliding samples crosses zero (exact for an exactly Coulomb slide, whatever the step).
double stick_time(const std::vector<Sample>& samples) {
  if (samples.size() < 3) return kNaN;
  const double dt = samples[1].t - samples[0].t;
  const double threshold = 0.5 * 3.5 * kSphere.mu * kG * dt;
  std::size_t last = samples.size();
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (!(slip(samples[k]) > threshold)) break;
    last = k;
  }
  if (last == samples.size() || last == 0 || last + 1 == samples.size()) return kNaN;
  const double s0 = slip(samples[last - 1]), s1 = slip(samples[last]);
  if (!(s0 > s1)) return kNaN;
  return samples[last].t + s1 / (s0 - s1) * (samples[last].t - samples[last - 1].t);
}
}  // namespace

std::string problem_name(Problem problem) {
  switch (problem) {
    case Problem::sphere:
      return "sphere";
    case Problem::slope_hold:
      return "slope_hold";
    case Problem::slope_slide:
      return "slope_slide";
  }
  return "?";
}

double slope_rad() { return kSlopeDeg * std::numbers::pi / 180.0; }

void gravity_of(Problem problem, double g[3]) {
  const double a = problem == Problem::sphere ? 0.0 : slope_rad();
  g[0] = kG * std::sin(a);
  g[1] = 0.0;
  g[2] = -kG * std::cos(a);
}

double mu_of(Problem problem) {
  switch (problem) {
    case Problem::sphere:
      return kSphere.mu;
    case Problem::slope_hold:
      return 0.5;
    case Problem::slope_slide:
      return 0.2;
  }
  return 0.0;
}

double sphere_stick_time() { return 2.0 * kSphere.v0 / (7.0 * kSphere.mu * kG); }
double sphere_final_speed() { return 5.0 / 7.0 * kSphere.v0; }
double slide_acceleration() {
  return kG * (std::sin(slope_rad()) - mu_of(Problem::slope_slide) * std::cos(slope_rad()));
}

Plan plan_of(Problem problem, bool quick) {
  switch (problem) {
    case Problem::sphere:
      return {quick ? 0.7 : 1.0, 0.0};
    case Problem::slope_hold:
      return {quick ? 2.0 : 100.0, 0.1};
    case Problem::slope_slide:
      return {quick ? 1.0 : 3.0, 0.01};
  }
  return {0.0, 0.0};
}

Errors measure(Problem problem, const std::vector<Sample>& samples, bool quick) {
  if (samples.size() < 2) return {kNaN, kNaN};
  const Sample& end = samples.back();
  for (double x : {end.p[0], end.p[2], end.v[0]}) {
    if (!std::isfinite(x)) return {kNaN, kNaN};
  }
  switch (problem) {
    case Problem::sphere:
      return {stick_time(samples) - sphere_stick_time(),
              (end.v[0] - sphere_final_speed()) / sphere_final_speed()};
    case Problem::slope_hold: {
      const double settled = quick ? 1.0 : 20.0;
      return {std::abs(end.p[0] - samples.front().p[0]),
              std::abs(end.p[0] - at(samples, settled).p[0])};
    }
    case Problem::slope_slide: {
      const Sample& a = at(samples, quick ? 0.5 : 1.0);
      const double acceleration = (end.v[0] - a.v[0]) / (end.t - a.t);
      return {(acceleration - slide_acceleration()) / slide_acceleration(), 0.0};
    }
  }
  return {kNaN, kNaN};
}

std::string describe(Problem problem, const Errors& e) {
  char text[160];
  switch (problem) {
    case Problem::sphere:
      std::snprintf(text, sizeof text, "stick time %+.2g s, final speed %+.2g rel", e.first,
                    e.second);
      break;
    case Problem::slope_hold:
      std::snprintf(text, sizeof text, "creep %.2g m, after settling %.2g m", e.first, e.second);
      break;
    case Problem::slope_slide:
      std::snprintf(text, sizeof text, "acceleration %+.2g rel", e.first);
      break;
  }
  return text;
}

}  // namespace stiction::peers
