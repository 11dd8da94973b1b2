#include "pendulum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

namespace stiction::peers {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct State {
  double angle, rate;
};

// Angular acceleration while the bar moves in direction `sign` (the friction opposes it).
double acceleration(double angle, double sign) {
  const PendulumParams& p = kPendulum;
  return (-p.mass * kG * p.com() * std::sin(angle) - sign * p.friction) / p.inertia();
}

State rk4(State x, double h, double sign) {
  auto f = [sign](State s) { return State{s.rate, acceleration(s.angle, sign)}; };
  const State k1 = f(x);
  const State k2 = f({x.angle + 0.5 * h * k1.angle, x.rate + 0.5 * h * k1.rate});
  const State k3 = f({x.angle + 0.5 * h * k2.angle, x.rate + 0.5 * h * k2.rate});
  const State k4 = f({x.angle + h * k3.angle, x.rate + h * k3.rate});
  return {x.angle + h / 6 * (k1.angle + 2 * k2.angle + 2 * k3.angle + k4.angle),
          x.rate + h / 6 * (k1.rate + 2 * k2.rate + 2 * k3.rate + k4.rate)};
}

bool inside_band(double angle) {
  const PendulumParams& p = kPendulum;
  return p.mass * kG * p.com() * std::abs(std::sin(angle)) <= p.friction;
}

Swings integrate_reference(double duration) {
  constexpr double h = 1e-5;
  Swings out;
  State x{kPendulum.angle0, 0.0};
  double t = 0.0;
  // Released at rest outside the band: it starts towards the bottom.
  double sign = x.angle > 0 ? -1.0 : 1.0;
  while (t < duration) {
    const double step = std::min(h, duration - t);
    const State next = rk4(x, step, sign);
    if (next.rate * sign > 0) {
      x = next;
      t += step;
      continue;
    }
    // The rate reaches zero within this step: bisect the sub-step that lands on it.
    double lo = 0.0, hi = step;
    for (int i = 0; i < 200 && hi - lo > 1e-18; ++i) {
      const double mid = 0.5 * (lo + hi);
      (rk4(x, mid, sign).rate * sign > 0 ? lo : hi) = mid;
    }
    x = rk4(x, hi, sign);
    x.rate = 0.0;
    t += hi;
    out.turns.push_back({t, x.angle});
    if (inside_band(x.angle)) {
      out.stop_time = t;
      break;
    }
    sign = -sign;
  }
  out.rest_angle = x.angle;
  return out;
}
}  // namespace

double pendulum_angle(const Sample& s) { return std::atan2(s.p[0], -s.p[2]); }
double pendulum_rate(const Sample& s) { return -s.w[1]; }

const Swings& pendulum_reference(double duration) {
  static std::map<double, Swings> cache;
  auto it = cache.find(duration);
  if (it == cache.end()) it = cache.emplace(duration, integrate_reference(duration)).first;
  return it->second;
}

Swings swings_of(const std::vector<Sample>& samples) {
  Swings out;
  const std::size_t n = samples.size();
  if (n < 3) return out;
  auto rate = [&](std::size_t k) { return pendulum_rate(samples[k]); };
  out.rest_angle = pendulum_angle(samples.back());
  std::size_t i = 0;
  while (i < n && !(std::abs(rate(i)) > kMoving)) ++i;
  if (i == n) return out;  // never moved
  double sign = rate(i) > 0 ? 1.0 : -1.0;
  while (true) {
    std::size_t j = i;
    while (j + 1 < n && rate(j + 1) * sign > 0) ++j;
    if (j + 1 == n) {
      // No turning point before the end: still swinging, or creeping at a crawl.
      std::size_t m = n;
      while (m > i && !(std::abs(rate(m - 1)) > kMoving)) --m;
      if (m < n && m > i) {
        out.stop_time = samples[m].t;
        out.creeping = true;
      }
      return out;
    }
    // The turn lies between samples j and j + 1: extrapolate the swing's last two samples.
    const double dt = samples[j + 1].t - samples[j].t;
    const double a = j > i ? (rate(j) - rate(j - 1)) / (samples[j].t - samples[j - 1].t)
                           : (rate(j + 1) - rate(j)) / dt;
    double tau = a * sign < 0 ? -rate(j) / a : dt;
    tau = std::clamp(tau, 0.0, dt);
    out.turns.push_back({samples[j].t + tau,
                         pendulum_angle(samples[j]) + rate(j) * tau + 0.5 * a * tau * tau});
    std::size_t m = j + 1;
    while (m < n && !(std::abs(rate(m)) > kMoving)) ++m;
    if (m == n) {
      out.stop_time = out.turns.back().t;
      return out;
    }
    sign = rate(m) > 0 ? 1.0 : -1.0;
    i = m;
  }
}

Errors compare_swings(const Swings& engine, const Swings& reference) {
  Errors e;
  const std::size_t n = std::min(engine.turns.size(), reference.turns.size());
  e.first = 0.0;
  e.second = std::abs(engine.rest_angle - reference.rest_angle);
  for (std::size_t k = 0; k < n; ++k) {
    e.first = std::max(e.first, std::abs(engine.turns[k].t - reference.turns[k].t));
    e.second = std::max(e.second, std::abs(engine.turns[k].angle - reference.turns[k].angle));
  }
  if (n == 0) e.first = e.second = kNaN;
  e.third = engine.stop_time - reference.stop_time;
  char note[120] = "";
  if (engine.turns.size() != reference.turns.size()) {
    std::snprintf(note, sizeof note, "%zu turning points, reference %zu", engine.turns.size(),
                  reference.turns.size());
  }
  if (engine.creeping) {
    std::snprintf(note + std::strlen(note), sizeof note - std::strlen(note), "%screeps to rest",
                  note[0] ? ", " : "");
  }
  e.note = note;
  return e;
}

}  // namespace stiction::peers
