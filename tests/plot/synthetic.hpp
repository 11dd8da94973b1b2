// Synthetic runs for the figure tests: closed-form or toy-model trajectories with the columns
// of the real scenes, so the goldens test the plotting and not the physics.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/trajectory.hpp"

namespace stiction::plot::testing {

// Simulation I in closed form: a sphere dropped from 1.01 R that lands at t0 and then
// slips with friction mu*M*g until pure rolling at t_stick = t0 + 2 v0 / (7 mu g).
inline core::Trajectory sphere_run(double duration = 1.0) {
  const double g = 9.8, mu = 0.1, v0 = 2.0, R = 0.2, M = 0.3, K = 1e7;
  const double z_rest = R - M * g / K;
  const double t0 = std::sqrt(2 * 0.01 * R / g);
  const double t_stick = t0 + 2 * v0 / (7 * mu * g);
  core::Trajectory tr(
      {"t", "sphere.p.x", "sphere.p.z", "sphere.v.x", "sphere.w.y", "ground.slip.x", "ground.f.z"});
  for (int i = 0; i * 1e-3 <= duration + 1e-12; ++i) {
    const double t = i * 1e-3;
    const double s = std::clamp(t - t0, 0.0, t_stick - t0);  // time spent slipping
    const double v = v0 - mu * g * s;
    const double w = 2.5 * mu * g * s / R;
    const double z = t < t0 ? 1.01 * R - 0.5 * g * t * t : z_rest;
    const double slip = t < t0 ? v0 : v - w * R;
    const double x = v0 * std::min(t, t0) + (v0 * s - 0.5 * mu * g * s * s) +
                     (t > t_stick ? v * (t - t_stick) : 0.0);
    const double row[] = {t, x, z, v, w, std::max(0.0, slip), t < t0 ? 0.0 : M * g};
    tr.append(row);
  }
  return tr;
}

inline double sphere_stick_time() {
  return std::sqrt(2 * 0.01 * 0.2 / 9.8) + 2 * 2.0 / (7 * 0.1 * 9.8);
}

// The paper's motor torques (28c)-(28d).
inline double motor_torque(int joint, double t) {
  if (t < 4.0) return std::min(0.52, (joint == 0 ? 0.3 : 0.5) * t);
  return 0.336 + 0.144 * (joint == 0 ? std::sin(100 * t) : std::cos(100 * t));
}

// Two independent joints with inertia I and Coulomb friction F under the paper's torques,
// integrated with small explicit steps; `drift` adds a creep after t = 4.5 s (LuGre-like).
inline core::Trajectory arm_run(double duration, double drift = 0.0) {
  const double F = 0.5, dt = 1e-4;
  const double inertia[2] = {0.0045, 0.0085};
  double theta[2] = {0, 0}, omega[2] = {0, 0};
  core::Trajectory tr({"t", "arm.theta.0", "arm.theta.1", "arm.omega.0", "arm.omega.1",
                       "motor0.tau", "motor1.tau", "joint0.tau", "joint1.tau"});
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int k = 0; k <= steps; ++k) {
    const double t = k * dt;
    double friction[2];
    for (int j = 0; j < 2; ++j) {
      const double tau = motor_torque(j, t);
      if (omega[j] == 0.0 && std::abs(tau) <= F) {
        friction[j] = -tau;
      } else {
        friction[j] = -F * (omega[j] > 0 ? 1.0 : omega[j] < 0 ? -1.0 : (tau > 0 ? 1.0 : -1.0));
      }
    }
    if (k % 10 == 0) {
      const double creep = t > 4.5 ? drift * (t - 4.5) : 0.0;
      const double row[] = {t,          theta[0] + creep,   theta[1] - 0.7 * creep, omega[0],
                            omega[1],   motor_torque(0, t), motor_torque(1, t),     friction[0],
                            friction[1]};
      tr.append(row);
    }
    for (int j = 0; j < 2; ++j) {
      const double acc = (motor_torque(j, t) + friction[j]) / inertia[j];
      const double next = omega[j] + acc * dt;
      omega[j] = (omega[j] > 0 && next < 0) || (omega[j] < 0 && next > 0) ? 0.0 : next;
      theta[j] += omega[j] * dt;
    }
  }
  return tr;
}

}  // namespace stiction::plot::testing
