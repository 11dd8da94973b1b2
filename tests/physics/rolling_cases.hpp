// What the rolling and spinning resistance tests share (test_rolling_cylinder.cpp,
// test_rolling_pair.cpp): running a generated scene, reading an element's stick time and a
// vector column, printing the figures docs/friction_laws.md quotes, and random numbers.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "core/simulation.hpp"
#include "core/types.hpp"
#include "scene/scene.hpp"
#include "trajectory_rows.hpp"

namespace stiction::testing {

inline core::RunResult run_generated(const std::string& text, const char* file_name) {
  auto scene = scene::load_scene(scene::SceneSource::from_text(text, file_name));
  return core::simulate(*scene.network, scene.run);
}

// The first stick of `element`, -1 if it never sticks (or has no events).
inline double stick_time(const core::RunResult& r, const std::string& element) {
  for (const auto& h : r.slip_events) {
    if (h.component == element) return h.monitor.stick_time();
  }
  return -1.0;
}

inline core::Vec3 column3(const core::Trajectory& tr, const std::string& name, double t) {
  return {column_at(tr, name + ".x", t), column_at(tr, name + ".y", t),
          column_at(tr, name + ".z", t)};
}

// The figures docs/friction_laws.md quotes (printed with STICTION_FIGURES set).
inline void figure(const char* test, const char* integrator, const char* what, double value) {
  if (std::getenv("STICTION_FIGURES") != nullptr) {
    std::printf("%-10s %-9s %-52s %.3g\n", test, integrator, what, value);
  }
}

struct Random {
  std::mt19937 rng;
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); }
  // A random unit vector, uniform in direction.
  core::Vec3 unit() {
    core::Vec3 v;
    do {
      v = core::Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    } while (v.norm() < 0.1 || v.norm() > 1.0);
    return v.normalized();
  }
  // A random unit vector perpendicular to the unit vector n.
  core::Vec3 unit_normal_to(const core::Vec3& n) {
    const core::Vec3 v = unit();
    return (v - n.dot(v) * n).normalized();
  }
};

}  // namespace stiction::testing
