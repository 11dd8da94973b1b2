// Integrators as data (DESIGN section 6): one explicit Runge-Kutta stepper driven by a
// tableau, generalized as in the paper (eq. 21): stage r evaluates the network at
// x(k) + T * sum_j a_rj xi_j, at time kT + c_r T, and passes its own step size
// tau_r = T * d_r to every impedance. d_r is the fraction of the step over which the
// stage's state derivative is next applied: the paper's {T1..T4}/T = {1/2, 1/2, 1, 1} for
// RK4, and 1 for forward Euler (one stage, tau = T, which reproduces eq. 14 exactly).
#pragma once

#include <string>
#include <vector>

#include "core/network.hpp"

namespace stiction::core {

struct Tableau {
  std::string name;
  int stages = 0;
  std::vector<double> a;  // stages x stages, row-major, strictly lower triangular
  std::vector<double> b;  // weights
  std::vector<double> c;  // stage times
  std::vector<double> d;  // stage step sizes tau_r / T handed to the impedances
  int order = 0;
  // Stability interval on the imaginary axis (|lambda T| below this is stable for an
  // undamped oscillator); 0 when the method is unstable there (forward Euler).
  double imaginary_stability = 0.0;
};

const Tableau& euler_tableau();
const Tableau& heun_tableau();
const Tableau& rk4_tableau();
// Names accepted by tableau_by_name / make_stepper, for messages.
std::vector<std::string> integrator_names();
// Throws std::invalid_argument naming the known integrators.
const Tableau& tableau_by_name(const std::string& name);

class RungeKuttaStepper {
 public:
  RungeKuttaStepper(const Tableau& tableau, int state_dim);
  const Tableau& tableau() const { return tableau_; }
  // Advances x from time t by T in place, then projects it (quaternions).
  void step(Network& network, double t, double T, Vec& x);

 private:
  Tableau tableau_;
  std::vector<Vec> xi_;  // stage derivatives, allocated once
  Vec stage_x_;
};

}  // namespace stiction::core
