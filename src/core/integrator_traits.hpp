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
//   implicit          linearly implicit Euler for stiff elements, order 1 (implicit_euler.hpp)
#pragma once

#include <string>
#include <vector>

namespace stiction::core {

enum class Method { explicit_rk, symplectic_euler, adaptive_rk4, implicit_euler };

struct IntegratorTraits {
  std::string name;
  Method method = Method::explicit_rk;
  int order = 0;          // global order of accuracy on a smooth problem
  bool implicit = false;  // solves for the step's end state
  // Chooses its own steps from a tolerance: no fixed step to check or halve; its accuracy
  // companion tightens the tolerance instead.
  bool adaptive = false;
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
// The integrator a tolerance selects (the table's adaptive row).
const IntegratorTraits& adaptive_integrator();
// Whether `name` chooses its own steps (false for an unknown name).
bool is_adaptive(const std::string& name);

}  // namespace stiction::core
