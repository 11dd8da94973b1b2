#include "core/integrator_traits.hpp"

#include <stdexcept>

namespace stiction::core {

const std::vector<IntegratorTraits>& integrator_table() {
  static const std::vector<IntegratorTraits> table = {
      {"euler", Method::explicit_rk, 1, false, false},
      {"symplectic_euler", Method::symplectic_euler, 1, false, false},
      {"heun", Method::explicit_rk, 2, false, false},
      {"rk4", Method::explicit_rk, 4, false, false},
      {"rk4_adaptive", Method::adaptive_rk4, 4, false, true, 5},
      {"implicit", Method::implicit_euler, 1, true, false},
      {"sdirk2", Method::sdirk, 2, true, true, 2},
      {"sdirk4", Method::sdirk, 4, true, true, 4},
  };
  return table;
}

const IntegratorTraits* find_integrator(const std::string& name) {
  for (const IntegratorTraits& t : integrator_table()) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

const IntegratorTraits& integrator_traits(const std::string& name) {
  if (const IntegratorTraits* t = find_integrator(name)) return *t;
  std::string known;
  for (const IntegratorTraits& t : integrator_table()) known += (known.empty() ? "" : ", ") + t.name;
  throw std::invalid_argument("unknown integrator '" + name + "' (known: " + known + ")");
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const IntegratorTraits& t : integrator_table()) names.push_back(t.name);
  return names;
}

const IntegratorTraits& adaptive_integrator() {
  for (const IntegratorTraits& t : integrator_table()) {
    if (t.adaptive) return t;
  }
  throw std::logic_error("no adaptive integrator in the table");
}

std::vector<std::string> adaptive_integrator_names() {
  std::vector<std::string> names;
  for (const IntegratorTraits& t : integrator_table()) {
    if (t.adaptive) names.push_back(t.name);
  }
  return names;
}

bool is_adaptive(const std::string& name) {
  const IntegratorTraits* t = find_integrator(name);
  return t != nullptr && t->adaptive;
}

}  // namespace stiction::core
