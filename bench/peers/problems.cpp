#include "problems.hpp"

#include "pendulum.hpp"

#include <algorithm>
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
    if (!(slip_of(samples[k]) > threshold)) break;
    last = k;
  }
  if (last == samples.size() || last == 0 || last + 1 == samples.size()) return kNaN;
  const double s0 = slip_of(samples[last - 1]), s1 = slip_of(samples[last]);
  if (!(s0 > s1)) return kNaN;
  return samples[last].t + s1 / (s0 - s1) * (samples[last].t - samples[last - 1].t);
}
}  // namespace

double slip_of(const Sample& s) { return s.v[0] - kSphere.radius * s.w[1]; }

void StickWatch::add(double t, double slip) {
  if (done_) return;
  if (slip > threshold_) {
    t0_ = t1_;
    s0_ = s1_;
    t1_ = t;
    s1_ = slip;
    sliding_ = std::min(sliding_ + 1, 2);
    return;
  }
  done_ = true;
  if (sliding_ == 2 && s0_ > s1_) stick_time_ = t1_ + s1_ / (s0_ - s1_) * (t1_ - t0_);
}

std::string problem_name(Problem problem) {
  switch (problem) {
    case Problem::sphere:
      return "sphere";
    case Problem::slope_hold:
      return "slope_hold";
    case Problem::slope_slide:
      return "slope_slide";
    case Problem::spheres:
      return "spheres";
    case Problem::pendulum:
      return "pendulum";
  }
  return "?";
}

std::string case_name(const Case& c) {
  return c.problem == Problem::spheres ? "spheres N=" + std::to_string(c.count)
                                       : problem_name(c.problem);
}

double slope_rad() { return kSlopeDeg * std::numbers::pi / 180.0; }

void gravity_of(Problem problem, double g[3]) {
  const bool slope = problem == Problem::slope_hold || problem == Problem::slope_slide;
  const double a = slope ? slope_rad() : 0.0;
  g[0] = kG * std::sin(a);
  g[1] = 0.0;
  g[2] = -kG * std::cos(a);
}

double mu_of(Problem problem) {
  switch (problem) {
    case Problem::sphere:
    case Problem::spheres:
      return kSphere.mu;
    case Problem::slope_hold:
      return 0.5;
    case Problem::slope_slide:
      return 0.2;
    case Problem::pendulum:
      return 0.0;  // joint friction: a torque bound, kPendulum.friction
  }
  return 0.0;
}

double spheres_v0(int i, int n) { return n == 1 ? kSphere.v0 : 1.0 + 2.0 * i / (n - 1); }
double spheres_lane(int i) { return kLaneSpacing * i; }
double stick_time_of(double v0) { return 2.0 * v0 / (7.0 * kSphere.mu * kG); }

double sphere_stick_time() { return stick_time_of(kSphere.v0); }
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
    case Problem::spheres:  // the last sphere sticks at 0.874 s
      return {1.0, 0.0};
    case Problem::pendulum:  // the reference stops at 7.0 s
      return {quick ? 2.0 : 9.0, 0.0};
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
    case Problem::pendulum:
      return compare_swings(swings_of(samples), pendulum_reference(end.t));
    case Problem::spheres:  // watched, not recorded: see StickWatch
      break;
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
    case Problem::spheres:
      std::snprintf(text, sizeof text, "stick time rel: max %.2g, mean %.2g%s", e.first,
                    e.second, e.third > 0 ? (", " + std::to_string(static_cast<int>(e.third)) +
                                             " never stuck").c_str()
                                          : "");
      break;
    case Problem::pendulum:
      std::snprintf(text, sizeof text, "phase %.2g s, amplitude %.2g rad, stop %+.2g s%s%s",
                    e.first, e.second, e.third, e.note.empty() ? "" : "; ", e.note.c_str());
      break;
  }
  return text;
}

}  // namespace stiction::peers
