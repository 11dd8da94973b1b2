// Admittance component (paper eq. 6): force in, motion out, x_dot = A(x, u_hat).
// x is the component's slice of the system state, u_hat the sum of the generalized forces
// that the wiring (Phi) applied to it during this evaluation.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/signal.hpp"
#include "core/types.hpp"

namespace stiction::core {

class Admittance {
 public:
  explicit Admittance(std::string name) : name_(std::move(name)) {}
  virtual ~Admittance() = default;
  Admittance(const Admittance&) = delete;
  Admittance& operator=(const Admittance&) = delete;

  const std::string& name() const { return name_; }
  virtual std::string_view type() const = 0;

  virtual int state_size() const = 0;
  virtual int input_size() const = 0;
  // One label per state slot ("p.x", "q.w", "theta.1", ...), for `stiction check`.
  virtual std::vector<std::string> state_labels() const = 0;

  // Which state slots are velocities (their derivative is an acceleration), for partitioned
  // integrators such as symplectic Euler. The default reads the labels: "v.*", "w.*" and
  // "omega.*" are velocities.
  virtual std::vector<bool> velocity_slots() const;

  virtual void initial_state(VecRef x) const = 0;
  virtual void derivative(ConstVecRef x, ConstVecRef u_hat, VecRef x_dot) const = 0;
  // The same on plain pointers to the slices, for the network's hot loop: views passed by
  // value go through the stack, where they can alias the heap stores around them. The
  // default wraps the pointers in views.
  virtual void derivative_at(const double* x, const double* u_hat, double* x_dot) const {
    derivative(Eigen::Map<const Vec>(x, state_size()), Eigen::Map<const Vec>(u_hat, input_size()),
               Eigen::Map<Vec>(x_dot, state_size()));
  }
  // Whether derivative(x, u_hat) is affine in u_hat at a fixed x, as for every body whose
  // input is a force: M(x)^-1 (u_hat - c(x)). The implicit step then forms a body's column
  // of its matrix from the elements touching that body alone (core/jacobian_pattern.hpp: a
  // neighbour's rate changes by the same amount whatever the other forces on it). The
  // default is false: an admittance opts in once its rate is known to be affine.
  virtual bool affine_in_input() const { return false; }
  // Called once after every full step: bring the state back to its manifold (unit
  // quaternions). Never inside a derivative, so RK stages see plain vector arithmetic.
  virtual void project(VecRef /*x*/) const {}
  // For an implicit Euler step x = start + h A(x, u_hat): sets the entries of `iterate` whose
  // equation involves the component's own state alone (kinematics: a quaternion given the
  // iterate's angular velocity) to that equation's exact solution. Newton's iteration with a
  // matrix kept over several steps converges on such rows only as fast as the matrix is fresh
  // (a rolling sphere's quaternion block goes stale as it turns); solved here, they follow the
  // other rows. The default leaves the iterate as it is.
  virtual void solve_kinematics(const double* /*start*/, double* /*iterate*/,
                                double /*h*/) const {}

  virtual std::vector<SignalInfo> signals() const = 0;
  virtual void write_signals(ConstVecRef x, VecRef out) const = 0;

  // Kinetic plus potential energy of the component alone (gravity included), for the
  // stability monitor; NaN when the component does not define one.
  virtual double energy(ConstVecRef /*x*/) const;

 private:
  std::string name_;
};

}  // namespace stiction::core
