#include "scene/friction_keys.hpp"

#include <sstream>
#include <string>
#include <vector>

namespace stiction::scene {

namespace {

std::string format(double v) {  // as toml_reader.cpp formats numbers in its messages
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

// The keys after the kinetic level (already in k.kinetic).
FrictionKeys read_levels(TableReader& table, FrictionKeys k, const char* kinetic_key,
                         const char* static_key) {
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

FrictionKeys read(TableReader& table, const char* kinetic_key, const char* static_key,
                  double default_kinetic) {
  FrictionKeys k;
  k.kinetic = table.non_negative(kinetic_key, default_kinetic);
  return read_levels(table, k, kinetic_key, static_key);
}

}  // namespace

FrictionKeys read_contact_friction(TableReader& table, double default_mu, bool surface) {
  const toml::node* mu = table.node("mu");
  if (mu == nullptr || !mu->is_array()) return read(table, "mu", "mu_static", default_mu);
  if (!surface) {
    table.fail("mu",
               "anisotropic friction ([mu_1, mu_2]) needs a surface: a contact between two "
               "bodies takes one coefficient");
  }
  const std::vector<double> pair = table.numbers("mu");
  if (pair.size() != 2) {
    std::string message =
        "expected one coefficient or two, [mu_1, mu_2] along `friction_axes` (got ";
    message += std::to_string(pair.size());
    message += " numbers)";
    table.fail("mu", message);
  }
  for (const double m : pair) {
    if (!(m > 0.0)) {
      std::string message = "each of [mu_1, mu_2] must be > 0 (got ";
      message += format(m);
      message += ")";
      table.fail("mu", message);
    }
  }
  if (pair[0] == pair[1]) {  // isotropic: exactly `mu = m`
    FrictionKeys k;
    k.kinetic = pair[0];
    k = read_levels(table, k, "mu", "mu_static");
    k.kinetic_2 = pair[1];
    return k;
  }
  // Over an ellipse, a static level or a rate-dependent one has no single definition
  // (which ellipse does mu_static scale, along which speed does the curve fall?): refused
  // rather than guessed.
  const char* why =
      " is not defined with anisotropic friction (`mu` = [mu_1, mu_2] with mu_1 != mu_2): the "
      "elliptic limit takes the kinetic level alone";
  if (table.has("mu_static")) {
    std::string message = "`mu_static`";
    message += why;
    table.fail("mu_static", message);
  }
  for (const char* key : {"stribeck_velocity", "viscous"}) {
    if (table.non_negative(key, 0.0) > 0.0) {
      std::string message = "`";
      message += key;
      message += "` > 0";
      message += why;
      table.fail(key, message);
    }
  }
  FrictionKeys k;
  k.kinetic = pair[0];
  k.static_level = pair[0];
  k.kinetic_2 = pair[1];
  return k;
}

FrictionKeys read_joint_friction(TableReader& table, double default_limit) {
  return read(table, "force_limit", "static_limit", default_limit);
}

}  // namespace stiction::scene
