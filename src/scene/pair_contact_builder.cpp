// [impedances.NAME] of type kikuuwe_contact with `other = "<body>"`: a contact between two
// bodies (issue 23) instead of a body and a plane. Pairs are declared, one table per pair:
// no broad phase looks for them (docs/components.md says what that costs). Sphere-sphere and
// sphere-box make one element NAME; box-box makes 16, NAME.0-7 for the corners of `body`
// against `other`'s faces and NAME.8-15 the other way round (pair_contact_map.hpp). With a
// sphere in the pair, `rolling_resistance` and `spin_friction` add NAME.rolling, NAME.spin.
// The law's keys are a plane contact's; the plane's own keys are refused here.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "components/impedance/pair_contact.hpp"
#include "components/impedance/pair_rolling_resistance.hpp"
#include "components/maps/pair_contact_map.hpp"
#include "components/maps/pair_twist_map.hpp"
#include "scene/components.hpp"
#include "scene/friction_keys.hpp"

namespace stiction::scene {

using core::Vec3;

namespace {

// `rolling_resistance` and `spin_friction` (m, >= 0) between two bodies: Kikuuwe elements on
// the first body's angular velocity relative to the second's
// (components/impedance/pair_rolling_resistance.hpp), for a sphere on a sphere or a box (one
// contact element, whose normal force is their N); a box on a box does not roll. The
// angular spring `rolling_stiffness` (default Kt R^2, N m/rad) and damper `rolling_damping`
// (default Bt R^2), R the smaller sphere's radius: the contact's tangential spring seen at
// the lever of the body that turns fastest for a given roll.
struct PairRolling {
  const char* suffix;
  components::RollingResistanceParams params;
};

// radius_a, radius_b: the bodies' sphere radii (0: not a sphere).
std::vector<PairRolling> read_pair_rolling(TableReader& table, double radius_a, double radius_b,
                                           const components::PairContactParams& p) {
  std::vector<PairRolling> out;
  if (!table.has("rolling_resistance") && !table.has("spin_friction")) {
    for (const char* key : {"rolling_stiffness", "rolling_damping"}) {
      if (table.has(key)) table.fail(key, "needs `rolling_resistance` or `spin_friction`");
    }
    return out;
  }
  const char* key = table.has("rolling_resistance") ? "rolling_resistance" : "spin_friction";
  if (!(radius_a > 0.0) && !(radius_b > 0.0)) {
    table.fail(key,
               "rolling and spinning resistance between two bodies need a sphere in the pair "
               "(sphere-sphere or sphere-box; a box does not roll on a box)");
  }
  double radius = 0.0;
  for (const double r : {radius_a, radius_b}) {
    if (r > 0.0 && (radius == 0.0 || r < radius)) radius = r;
  }
  const double kt = p.tangential_stiffness > 0.0 ? p.tangential_stiffness : p.stiffness;
  const double bt = p.tangential_damping >= 0.0 ? p.tangential_damping : p.damping;
  components::RollingResistanceParams base;
  base.radius = radius;
  base.stiffness = table.positive("rolling_stiffness", kt * radius * radius);
  base.damping = table.non_negative("rolling_damping", bt * radius * radius);
  if (table.has("rolling_resistance")) {
    PairRolling r{"rolling", base};
    r.params.part = components::RollingPart::rolling;
    r.params.coefficient = table.non_negative("rolling_resistance", 0.0);
    out.push_back(r);
  }
  if (table.has("spin_friction")) {
    PairRolling r{"spin", base};
    r.params.part = components::RollingPart::spin;
    r.params.coefficient = table.non_negative("spin_friction", 0.0);
    out.push_back(r);
  }
  return out;
}

}  // namespace

void ComponentBuilder::add_pair_contact(TableReader& table, const std::string& name) {
  for (const char* key : {"normal", "offset", "extent", "belt_speed", "belt_direction", "tilt",
                          "tilt_axis", "tilt_pivot", "points", "radius", "settle", "initial_e"}) {
    if (table.has(key)) {
      table.fail(key, std::string("`") + key +
                          "` describes a contact with a plane; a contact between bodies "
                          "(`other`) takes its geometry from the two bodies' shapes");
    }
  }
  const BodyInfo& a = body(table, "body");
  const core::Body* body_a = pose_body(table, "body");
  const BodyInfo& b = body(table, "other");
  const core::Body* body_b = pose_body(table, "other");
  if (body_a == body_b) table.fail("other", "must name a body other than `body`");
  auto shape_of = [&](const BodyInfo& info, std::string_view key) {
    if (info.sphere_radius > 0.0) return 's';
    if (info.box_size != Vec3::Zero()) return 'b';
    table.fail(key, "'" + info.admittance->name() +
                        "' has no shape a contact between bodies supports (supported: a "
                        "rigid_body of shape sphere, hollow_sphere or box)");
  };
  const char sa = shape_of(a, "body"), sb = shape_of(b, "other");

  components::PairContactParams p;
  p.stiffness = table.positive("stiffness", p.stiffness);
  p.damping = table.non_negative("damping", p.damping);
  const FrictionKeys friction = read_contact_friction(table, p.mu);
  p.mu = friction.kinetic;
  p.mu_static = friction.static_level;
  p.stribeck_velocity = friction.stribeck_velocity;
  p.viscous = friction.viscous;
  if (table.has("tangential_stiffness"))
    p.tangential_stiffness = table.positive("tangential_stiffness", 0.0);
  if (table.has("tangential_damping"))
    p.tangential_damping = table.non_negative("tangential_damping", 0.0);
  const double threshold = table.positive("stick_threshold", 1e-3);
  const std::vector<PairRolling> rolling =
      read_pair_rolling(table, a.sphere_radius, b.sphere_radius, p);
  table.finish();

  components::PairShape shape;
  shape.radius_a = a.sphere_radius;
  shape.radius_b = b.sphere_radius;
  shape.half_a = 0.5 * a.box_size;
  shape.half_b = 0.5 * b.box_size;
  shape.kind = sa == 's' ? (sb == 's' ? components::PairKind::sphere_sphere
                                      : components::PairKind::sphere_box)
                         : (sb == 's' ? components::PairKind::box_sphere
                                      : components::PairKind::box_box);
  const int count = shape.kind == components::PairKind::box_box ? 16 : 1;
  p.gap_is_distance = shape.kind != components::PairKind::box_box;
  count_contact_elements(table, static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const std::string element = count > 1 ? name + "." + std::to_string(i) : name;
    shape.corner = i;
    std::unique_ptr<core::Impedance> contact;
    try {
      contact = std::make_unique<components::PairContact>(element, p);
    } catch (const std::invalid_argument& e) {
      throw InputError::at(table.table().source(), table.path() + ": " + e.what());
    }
    stick_thresholds_[element] = threshold;
    impedance_types_.emplace(element, "kikuuwe_contact");
    add_element(std::move(contact),
                std::make_unique<components::PairContactMap>(*body_a, *body_b, shape));
    ContactSite site;  // drawn where probe_pair puts the contact point
    site.rule = ContactSite::Rule::pair;
    site.name = element;
    site.group = name;
    site.body = body_index(drawing_, body_a->name());
    site.other = body_index(drawing_, body_b->name());
    site.pair = shape;
    drawing_.sites.contacts.push_back(std::move(site));
  }
  // Rolling and spinning resistance on the relative angular velocity: NAME.rolling, NAME.spin.
  for (const PairRolling& r : rolling) {
    const std::string element = name + "." + r.suffix;
    std::unique_ptr<core::Impedance> resistance;
    try {
      resistance = std::make_unique<components::PairRollingResistance>(element, p, r.params);
    } catch (const std::invalid_argument& e) {
      throw InputError::at(table.table().source(), table.path() + ": " + e.what());
    }
    stick_thresholds_[element] = threshold;
    impedance_types_.emplace(element, "kikuuwe_contact");
    add_element(std::move(resistance),
                std::make_unique<components::PairTwistMap>(*body_a, *body_b, shape));
  }
  impedance_types_.emplace(name, "kikuuwe_contact");
}

}  // namespace stiction::scene
