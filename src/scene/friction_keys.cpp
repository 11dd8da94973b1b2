#include "scene/friction_keys.hpp"

#include <sstream>
#include <string>

namespace stiction::scene {

namespace {

std::string format(double v) {  // as toml_reader.cpp formats numbers in its messages
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

FrictionKeys read(TableReader& table, const char* kinetic_key, const char* static_key,
                  double default_kinetic) {
  FrictionKeys k;
  k.kinetic = table.non_negative(kinetic_key, default_kinetic);
  k.static_level = table.non_negative(static_key, k.kinetic);
  if (!(k.static_level >= k.kinetic)) {
    // Built by appending: GCC 12 warns falsely on "literal" + std::string (-Wrestrict).
    std::string message = "must be >= `";
    message += kinetic_key;
    message += "` (";
    message += format(k.kinetic);
    message += "): friction breaks away at the static level and slides at the kinetic one (got ";
    message += format(k.static_level);
    message += ")";
    table.fail(static_key, message);
  }
  k.stribeck_velocity = table.non_negative("stribeck_velocity", 0.0);
  k.viscous = table.non_negative("viscous", 0.0);
  return k;
}

}  // namespace

FrictionKeys read_contact_friction(TableReader& table, double default_mu) {
  return read(table, "mu", "mu_static", default_mu);
}

FrictionKeys read_joint_friction(TableReader& table, double default_limit) {
  return read(table, "force_limit", "static_limit", default_limit);
}

}  // namespace stiction::scene
