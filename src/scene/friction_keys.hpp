// The keys of a friction law (components/impedance/friction_law.hpp), read alike by every
// builder that makes a Kikuuwe element:
// - contacts (plane, moving, between bodies): `mu` (kinetic), `mu_static` (default `mu`),
//   `stribeck_velocity` (m/s, 0 = none), `viscous` (N s/m);
// - kikuuwe_friction (joints and points): `force_limit` (kinetic level), `static_limit`
//   (default `force_limit`), `stribeck_velocity`, `viscous`.
// Each is finite and >= 0, and the static value is at least the kinetic one; an error names
// the file, the line and the key.
#pragma once

#include "scene/toml_reader.hpp"

namespace stiction::scene {

struct FrictionKeys {
  double kinetic = 0.0;       // mu or force_limit (a contact's mu_1 when anisotropic)
  double static_level = 0.0;  // mu_static or static_limit (= kinetic when absent)
  double stribeck_velocity = 0.0;
  double viscous = 0.0;
  // `mu = [mu_1, mu_2]` (issue 38 item 2): mu_2, or -1 for a number. mu_1 == mu_2 is the
  // isotropic law itself (and takes mu_static, Stribeck and viscous friction as such).
  double kinetic_2 = -1.0;
  bool anisotropic() const { return kinetic_2 >= 0.0 && kinetic_2 != kinetic; }
};

// `mu`, `mu_static`, `stribeck_velocity`, `viscous`; `mu` defaults to `default_mu`. With
// `surface` (a contact with a plane), `mu` may be `[mu_1, mu_2]`, each > 0: anisotropic
// friction with an elliptic limit, which goes with the kinetic level alone (`mu_static`,
// `stribeck_velocity` > 0 or `viscous` > 0 beside unequal entries are errors at their key).
FrictionKeys read_contact_friction(TableReader& table, double default_mu, bool surface = false);

// `force_limit`, `static_limit`, `stribeck_velocity`, `viscous`; `force_limit` defaults to
// `default_limit`.
FrictionKeys read_joint_friction(TableReader& table, double default_limit);

}  // namespace stiction::scene
