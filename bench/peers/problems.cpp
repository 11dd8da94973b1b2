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
    case Problem::ramp_grid:
      return "ramp_grid";
    case Problem::pinch:
      return "pinch";
  }
  return "?";
}

std::string case_name(const Case& c) {
  char text[96];
  switch (c.problem) {
    case Problem::spheres:
      return "spheres N=" + std::to_string(c.count);
    case Problem::ramp_grid:
      if (c.breakaway) {
        std::snprintf(text, sizeof text, "ramp_grid mu=%g breakaway", c.mu);
      } else {
        std::snprintf(text, sizeof text, "ramp_grid mu=%g tan/mu=%.3g", c.mu,
                      std::tan(c.angle) / c.mu);
      }
      return text;
    case Problem::pinch:
      std::snprintf(text, sizeof text, "pinch margin=%g", c.margin);
      return text;
    default:
      return problem_name(c.problem);
  }
}

bool box_on_plane(Problem problem) {
  return problem == Problem::slope_hold || problem == Problem::slope_slide ||
         problem == Problem::ramp_grid;
}

double slope_rad() { return kSlopeDeg * std::numbers::pi / 180.0; }

void gravity_of(const Case& c, double g[3]) {
  const bool slope = c.problem == Problem::slope_hold || c.problem == Problem::slope_slide;
  const double a = slope ? slope_rad() : c.problem == Problem::ramp_grid ? c.angle : 0.0;
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
    case Problem::ramp_grid:
      return 0.5;
    case Problem::pinch:
      return kPinch.mu;
  }
  return 0.0;
}

double mu_of(const Case& c) {
  return c.problem == Problem::ramp_grid || c.problem == Problem::pinch ? c.mu
                                                                          : mu_of(c.problem);
}

std::vector<Case> ramp_cases(bool quick) {
  std::vector<Case> cases;
  for (double mu : kRampMus) {
    if (quick && mu != 0.5) continue;
    for (double ratio : kRampRatios) {
      if (quick && ratio != 0.9) continue;
      cases.push_back({Problem::ramp_grid, 1, mu, std::atan(ratio * mu), 0.0, false});
    }
  }
  for (double mu : kRampMus) {
    if (quick && mu != 0.5) continue;
    cases.push_back({Problem::ramp_grid, 1, mu, std::atan(mu), 0.0, true});
  }
  return cases;
}

std::vector<Case> pinch_cases(bool quick) {
  std::vector<Case> cases;
  for (double margin : kPinchMargins) {
    if (quick && margin != 2.0) continue;
    cases.push_back({Problem::pinch, 3, kPinch.mu, 0.0, margin, false});
  }
  return cases;
}

double breakaway_reference(double mu, bool quick) {
  const double mean = 0.5 * (settle_time(quick) + breakaway_duration(quick));
  return std::atan(mu) + std::asin(kBreakawaySpeed / (kG * mean * std::sqrt(1.0 + mu * mu)));
}

double settle_time(bool quick) { return quick ? 0.5 : 1.0; }
double breakaway_duration(bool quick) { return settle_time(quick) + (quick ? 1.0 : 2.0); }

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
    case Problem::ramp_grid:  // creep over 10 s after settling
    case Problem::pinch:
      return {settle_time(quick) + (quick ? 1.0 : 10.0), 0.1};
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
    case Problem::ramp_grid:  // measure_hold
    case Problem::pinch:
      break;
  }
  return {kNaN, kNaN};
}

Errors measure_hold(const Case& c, const std::vector<std::vector<Sample>>& samples, bool quick) {
  const std::vector<Sample>& block = samples.at(0);
  if (block.size() < 2) return {kNaN, kNaN, kNaN};
  // The coordinate whose creep counts: along the slope (x) on the ramp; the block's height
  // less the fingers' mean height in the pinch.
  auto coordinate = [&](std::size_t k) {
    if (c.problem == Problem::ramp_grid) return block[k].p[0];
    return block[k].p[2] - 0.5 * (samples.at(1)[k].p[2] + samples.at(2)[k].p[2]);
  };
  const std::size_t last = block.size() - 1;
  for (std::size_t k : {std::size_t{0}, last}) {
    if (!std::isfinite(coordinate(k)) || !std::isfinite(block[k].p[0])) return {kNaN, kNaN, kNaN};
  }
  const double settled = settle_time(quick);
  std::size_t from = 0;
  for (std::size_t k = 0; k <= last; ++k) {
    if (std::abs(block[k].t - settled) < std::abs(block[from].t - settled)) from = k;
  }
  const double creep = std::abs(coordinate(last) - coordinate(from)) / (block[last].t - block[from].t);
  const double moved = coordinate(last) - coordinate(0);
  return {creep, std::abs(moved), c.problem == Problem::pinch ? -moved : 0.0};
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
    case Problem::ramp_grid:
    case Problem::pinch:
      std::snprintf(text, sizeof text, "creep %.2g m/s, moved %.2g m", e.first, e.second);
      break;
  }
  return text;
}

}  // namespace stiction::peers
