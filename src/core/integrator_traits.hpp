// Every integrator's traits, declared once (issue 35 item 8; DESIGN section 2, "facts
// declared once"): a method is a row of this table and a `Method` value that the few places
// that build or analyse it switch on, as MuJoCo's mjtIntegrator is. No other file compares an
// integrator's name: they ask its row.
//
//   (name) => (method, order, implicit, adaptive)
//   euler             explicit RK, 1 stage, order 1
//   symplectic_euler  semi-implicit Euler, order 1
//   heun              explicit RK, 2 stages, order 2
//   rk4               explicit RK, 4 stages, order 4 (the paper's generalized RK4)
//   rk4_adaptive      RK4 with step doubling and error control: its step follows a tolerance
//   implicit          backward Euler for stiff elements, order 1 (implicit_euler.hpp)
//   sdirk2            Alexander's L-stable SDIRK, 2 stages, order 2, embedded order 1, error
//                     control at a tolerance (sdirk.hpp)
//   sdirk4            Hairer & Wanner's L-stable SDIRK, 5 stages, order 4, embedded order 3,
//                     error control at a tolerance (sdirk.hpp)
#pragma once

#include <string>
#include <vector>

namespace stiction::core {

enum class Method { explicit_rk, symplectic_euler, adaptive_rk4, implicit_euler, sdirk };

struct IntegratorTraits {
  std::string name;
  Method method = Method::explicit_rk;
  int order = 0;          // global order of accuracy on a smooth problem
  bool implicit = false;  // solves for the step's end state
  // Chooses its own steps from a tolerance: no fixed step to check or halve; its accuracy
  // companion tightens the tolerance instead.
  bool adaptive = false;
  // Adaptive only: the local error estimate its step control holds at the tolerance is
  // O(h^error_order), so steps scale as tolerance^(1 / error_order) (core/step_control.hpp):
  // order + 1 for step doubling, the embedded solution's order + 1 for an embedded pair.
  int error_order = 0;
  // Its fixed step has a stability limit the step analysis (core/stability.hpp) predicts.
  bool step_analysed() const { return !adaptive; }
};

// All integrators, in the order commands list them.
const std::vector<IntegratorTraits>& integrator_table();
// The row of `name`, or nullptr.
const IntegratorTraits* find_integrator(const std::string& name);
// The row of `name`; throws std::invalid_argument naming the known integrators.
const IntegratorTraits& integrator_traits(const std::string& name);
// The names of the table (for messages, option checks and `stiction study`).
std::vector<std::string> integrator_names();
// The integrator a tolerance selects when no adaptive one is named (the table's first
// adaptive row, rk4_adaptive).
const IntegratorTraits& adaptive_integrator();
// The names of the adaptive rows (for messages).
std::vector<std::string> adaptive_integrator_names();
// Whether `name` chooses its own steps (false for an unknown name).
bool is_adaptive(const std::string& name);

}  // namespace stiction::core
