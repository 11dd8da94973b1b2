#include "core/integrator.hpp"

#include <stdexcept>

namespace stiction::core {

const Tableau& euler_tableau() {
  static const Tableau t{"euler", 1, {0.0}, {1.0}, {0.0}, {1.0}, 1, 0.0};
  return t;
}

const Tableau& heun_tableau() {
  // Explicit trapezoid (RK2): the second stage is taken a full step ahead.
  static const Tableau t{"heun", 2, {0.0, 0.0, 1.0, 0.0}, {0.5, 0.5}, {0.0, 1.0}, {1.0, 1.0},
                         2, 0.0};
  return t;
}

const Tableau& rk4_tableau() {
  // Classic RK4 with the paper's stage sizes {T1..T4} = {T/2, T/2, T, T} (eq. 21).
  static const Tableau t{"rk4",
                         4,
                         {0, 0, 0, 0,  //
                          0.5, 0, 0, 0,  //
                          0, 0.5, 0, 0,  //
                          0, 0, 1, 0},
                         {1.0 / 6, 2.0 / 6, 2.0 / 6, 1.0 / 6},
                         {0.0, 0.5, 0.5, 1.0},
                         {0.5, 0.5, 1.0, 1.0},
                         4,
                         2.8284271247461903};
  return t;
}

std::vector<std::string> integrator_names() { return {"euler", "heun", "rk4"}; }

const Tableau& tableau_by_name(const std::string& name) {
  if (name == "euler") return euler_tableau();
  if (name == "heun") return heun_tableau();
  if (name == "rk4") return rk4_tableau();
  std::string known;
  for (const auto& n : integrator_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown integrator '" + name + "' (known: " + known + ")");
}

RungeKuttaStepper::RungeKuttaStepper(const Tableau& tableau, int state_dim)
    : tableau_(tableau), xi_(tableau.stages, Vec::Zero(state_dim)), stage_x_(state_dim) {}

void RungeKuttaStepper::step(Network& network, double t, double T, Vec& x) {
  const int s = tableau_.stages;
  for (int r = 0; r < s; ++r) {
    stage_x_ = x;
    for (int j = 0; j < r; ++j) {
      const double a = tableau_.a[r * s + j];
      if (a != 0.0) stage_x_.noalias() += (T * a) * xi_[j];
    }
    network.derivative(t + tableau_.c[r] * T, stage_x_, T * tableau_.d[r], xi_[r]);
  }
  for (int r = 0; r < s; ++r) {
    if (tableau_.b[r] != 0.0) x.noalias() += (T * tableau_.b[r]) * xi_[r];
  }
  network.project(x);
}

}  // namespace stiction::core
