// [impedances.NAME] of type kikuuwe_contact: a contact surface (plane, optional extent,
// optional belt and tilt) and the body points that touch it. One Kikuuwe contact element per
// point, each with its own friction state and events: `NAME` for a single point, `NAME.i`
// for the points of a `points` list, a box's corners or a cylinder's rim points. docs/scene_format.md lists the keys.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "components/admittance/clock.hpp"
#include "components/admittance/rigid_body.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "components/impedance/moving_contact.hpp"
#include "components/impedance/rolling_resistance.hpp"
#include "components/maps/body_twist_map.hpp"
#include "components/maps/contact_point_map.hpp"
#include "components/maps/cylinder_rim_map.hpp"
#include "components/maps/cylinder_twist_map.hpp"
#include "components/maps/surface_point_map.hpp"
#include "core/safe_normalize.hpp"
#include "scene/components.hpp"
#include "scene/friction_keys.hpp"
#include "scene/expression.hpp"

namespace stiction::scene {

using core::Vec3;

namespace {

// Contact points per contact (issue 25): measured peak memory of `run --no-plots` on a box with
// 1000 and 10000 listed points over 101 output rows, less `check`'s: 51-52 kB a point (the
// elements, their output columns, events and the summary). 10000 points: about 0.5 GB, 30 s
// for 2000 steps.
constexpr std::size_t kMaxContactPoints = 10000;
constexpr double kBytesPerContactPoint = 51e3;
// Contact elements in a whole scene (issue 39): about 1 GB of a run's memory at that figure.
constexpr std::size_t kMaxSceneContactElements = 20000;

// Components check their own parameters too: report what they reject at the table.
template <typename Make>
auto construct_contact(TableReader& table, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    throw InputError::at(table.table().source(), table.path() + ": " + e.what());
  }
}

// A number, or an expression of t (string), as a profile.
std::function<double(double)> time_profile(TableReader& table, std::string_view key) {
  const toml::node* node = table.node(key);
  if (node->is_number()) {
    const double value = finite_number(*node, table.path() + "." + std::string(key));
    return [value](double) { return value; };
  }
  if (!node->is_string()) table.fail(key, "expected a number or an expression of t (a string)");
  auto expression = std::make_shared<Expression>(node->as_string()->get(), node->source(),
                                                 table.path() + "." + std::string(key));
  return [expression](double t) { return expression->evaluate(t); };
}

// Two numbers; infinities allowed (TOML `inf`, `-inf`), NaN not.
std::array<double, 2> bound_pair(TableReader& table, std::string_view key, double fallback) {
  const toml::node* node = table.node(key);
  if (node == nullptr) return {fallback, fallback};
  const toml::array* a = node->as_array();
  if (a == nullptr || a->size() != 2) table.fail(key, "expected 2 numbers [u, v] (inf allowed)");
  std::array<double, 2> out{};
  for (std::size_t i = 0; i < 2; ++i) {
    out[i] = number_or_infinity((*a)[i], table.path() + "." + std::string(key));
  }
  return out;
}

components::SurfaceExtent read_extent(TableReader& contact, const Vec3& n, double offset) {
  components::SurfaceExtent extent;
  std::optional<TableReader> table = contact.subtable("extent");
  if (!table) return extent;
  extent.centre = table->vec3("centre", offset * n);
  extent.centre -= n.dot(extent.centre - offset * n) * n;  // onto the plane
  const Vec3 seed = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 axis = table->vec3("axis", seed);
  const Vec3 u = axis - n.dot(axis) * n;
  if (!(u.norm() > 1e-9 * std::max(1.0, axis.norm()))) {
    table->fail("axis", "must be a direction in the surface plane (not along the normal)");
  }
  extent.u = u.normalized();
  extent.v = n.cross(extent.u);
  const double inf = std::numeric_limits<double>::infinity();
  const auto lo = bound_pair(*table, "min", -inf);
  const auto hi = bound_pair(*table, "max", inf);
  extent.u_min = lo[0];
  extent.v_min = lo[1];
  extent.u_max = hi[0];
  extent.v_max = hi[1];
  if (!(extent.u_min < extent.u_max) || !(extent.v_min < extent.v_max)) {
    table->fail("max", "must exceed `min` in both coordinates");
  }
  table->finish();
  if (!extent.bounded())
    table->fail("max", "an extent needs at least one finite bound in `min` or `max`");
  return extent;
}

// A cylinder's rim points follow its orientation (cylinder_rim_map.hpp): the moving surfaces'
// maps and `settle` work on fixed body points, so neither takes a cylinder yet.
void reject_for_cylinder(TableReader& table, bool moving, bool settle) {
  if (moving) {
    table.fail(table.has("belt_speed") ? "belt_speed" : "tilt",
               "a moving surface does not support a cylinder body yet (fixed planes only)");
  }
  if (settle) table.fail("settle", "not supported for a cylinder body (start it at rest on the plane)");
}

// `rolling_resistance` and `spin_friction` (m, >= 0): Kikuuwe elements on the body's
// angular velocity (components/impedance/rolling_resistance.hpp), for a sphere (one contact
// point) or a cylinder (its rim points, `rim` its shape) on a fixed plane; `other_shape`
// says a sphere's contact is anything else (several or listed points, a moving surface).
// The angular spring `rolling_stiffness` (default Kt R^2, N m/rad) and damper
// `rolling_damping` (default Bt R^2, N m s/rad): the contact's own tangential spring seen at
// the lever R (the sphere's or the cylinder's radius).
// The element reads the cylinder's x_hat as the map lays it out.
static_assert(components::CylinderTwistMap::kAxisOffset == components::kCylinderAxis &&
              components::CylinderTwistMap::kRimOffset == components::kCylinderRim &&
              components::CylinderTwistMap::kSize == components::kCylinderInput);

struct RollingElement {
  const char* suffix;
  components::RollingResistanceParams params;
};

std::vector<RollingElement> read_rolling_resistance(TableReader& table, double sphere_radius,
                                                    const components::CylinderShape* rim,
                                                    const core::Body& body,
                                                    const components::KikuuweContactParams& p,
                                                    double radius, bool other_shape) {
  std::vector<RollingElement> out;
  const bool any = table.has("rolling_resistance") || table.has("spin_friction");
  if (!any) {
    for (const char* key : {"rolling_stiffness", "rolling_damping"}) {
      if (table.has(key)) table.fail(key, "needs `rolling_resistance` or `spin_friction`");
    }
    return out;
  }
  const char* key = table.has("rolling_resistance") ? "rolling_resistance" : "spin_friction";
  const bool sphere = sphere_radius > 0.0 && !other_shape && body.can_rotate() && radius > 0.0;
  if (!sphere && rim == nullptr) {
    table.fail(key,
               "rolling and spinning resistance are supported for a rigid_body sphere (one "
               "contact point) or cylinder (its rim points) on a fixed plane only (no "
               "`points`, `belt_speed` or `tilt`)");
  }
  if (rim != nullptr) radius = rim->radius;
  const double kt = p.tangential_stiffness > 0.0 ? p.tangential_stiffness : p.stiffness;
  const double bt = p.tangential_damping >= 0.0 ? p.tangential_damping : p.damping;
  components::RollingResistanceParams base;
  base.body = rim != nullptr ? components::RollingBody::cylinder : components::RollingBody::sphere;
  base.radius = radius;
  base.stiffness = table.positive("rolling_stiffness", kt * radius * radius);
  base.damping = table.non_negative("rolling_damping", bt * radius * radius);
  if (table.has("rolling_resistance")) {
    RollingElement r{"rolling", base};
    r.params.part = components::RollingPart::rolling;
    r.params.coefficient = table.non_negative("rolling_resistance", 0.0);
    out.push_back(r);
  }
  if (table.has("spin_friction")) {
    RollingElement r{"spin", base};
    r.params.part = components::RollingPart::spin;
    r.params.coefficient = table.non_negative("spin_friction", 0.0);
    out.push_back(r);
  }
  return out;
}

// `friction_axes = [[x, y, z], [x, y, z]]` and `friction_axes_frame = "world" | "body"`
// (issue 38 item 2): the directions of mu_1 and mu_2 of `mu = [mu_1, mu_2]`, two orthogonal
// directions in the surface. World axes are taken on the surface at rest (a tilting surface
// carries them along); body axes turn with the body and must lie in the surface at its
// initial pose. Without the key: the surface's own tangents (t1 = world x on the plane, or
// world y when the normal is close to x; t2 = n x t1). Returns mu_1's direction (world or
// body frame; zero for the surface's t1).
struct FrictionAxes {
  Vec3 first = Vec3::Zero();
  bool body = false;
};

std::string degrees_text(double radians) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", radians * 180.0 / M_PI);
  return text;
}

FrictionAxes read_friction_axes(TableReader& table, const FrictionKeys& friction, const Vec3& n,
                                const core::Admittance& admittance, const core::Body& body) {
  FrictionAxes out;
  if (friction.kinetic_2 < 0.0) {
    for (const char* key : {"friction_axes", "friction_axes_frame"}) {
      if (table.has(key)) table.fail(key, "needs `mu = [mu_1, mu_2]` (anisotropic friction)");
    }
    return out;
  }
  const std::string frame = table.string("friction_axes_frame", "world");
  if (frame != "world" && frame != "body") {
    table.fail("friction_axes_frame", "expected \"world\" or \"body\"");
  }
  out.body = frame == "body";
  if (out.body && !body.can_rotate()) {
    table.fail("friction_axes_frame", "a point_mass has no orientation: use \"world\" axes");
  }
  const toml::node* node = table.node("friction_axes");
  if (node == nullptr) {
    if (out.body) table.fail("friction_axes_frame", "body-fixed axes need `friction_axes`");
    return out;
  }
  const toml::array* a = node->as_array();
  std::array<Vec3, 2> axes;
  bool ok = a != nullptr && a->size() == 2;
  for (std::size_t i = 0; ok && i < 2; ++i) {
    const toml::array* xyz = (*a)[i].as_array();
    ok = xyz != nullptr && xyz->size() == 3;
    for (std::size_t j = 0; ok && j < 3; ++j) {
      ok = (*xyz)[j].is_number();
      if (ok)
        axes[i][static_cast<int>(j)] = finite_number((*xyz)[j], table.path() + ".friction_axes");
    }
  }
  if (!ok) table.fail("friction_axes", "expected two directions [[x, y, z], [x, y, z]]");
  for (const Vec3& axis : axes) {
    if (!(axis.norm() > 0.0)) table.fail("friction_axes", "each axis must be a non-zero direction");
  }
  const double cosine = axes[0].dot(axes[1]) / (axes[0].norm() * axes[1].norm());
  if (!(std::abs(cosine) <= 1e-6)) {
    std::string message = "the two axes must be orthogonal (they are ";
    message += degrees_text(std::acos(std::clamp(cosine, -1.0, 1.0)));
    message += " degrees apart)";
    table.fail("friction_axes", message);
  }
  // In the surface: world axes as given, body axes at the body's initial pose.
  core::Quat q0 = core::Quat::Identity();
  if (out.body) {
    core::Vec y(admittance.state_size());
    admittance.initial_state(y);
    q0 = body.motion(y).q;
  }
  for (std::size_t i = 0; i < 2; ++i) {
    const Vec3 world = q0 * axes[i];
    const double sine = n.dot(world) / world.norm();
    if (!(std::abs(sine) <= 1e-6)) {
      std::string message = "axis ";
      message += std::to_string(i + 1);
      message += " is not in the surface (";
      message += degrees_text(std::asin(std::clamp(sine, -1.0, 1.0)));
      message += out.body ? " degrees out of its plane at the body's initial pose)"
                          : " degrees out of its plane)";
      table.fail("friction_axes", message);
    }
  }
  out.first = axes[0];
  return out;
}

}  // namespace

void ComponentBuilder::count_contact_elements(TableReader& table, std::size_t count) {
  contact_elements_ += count;
  if (contact_elements_ <= kMaxSceneContactElements) return;
  char estimate[64];
  std::snprintf(estimate, sizeof estimate, "%.1f GB",
                static_cast<double>(contact_elements_) * kBytesPerContactPoint / 1e9);
  throw InputError::at(
      table.table().source(),
      table.path() + ": the scene's contacts reach " + std::to_string(contact_elements_) +
          " contact elements here (points, corners, rim points and body pairs; about " +
          estimate + " of memory, " +
          std::to_string(static_cast<int>(kBytesPerContactPoint / 1000)) +
          " kB each); the limit is " + std::to_string(kMaxSceneContactElements) +
          " in a scene (docs/limits.md): declare only the pairs that can touch");
}

void ComponentBuilder::add_contact(TableReader& table, const std::string& name) {
  if (table.has("other")) return add_pair_contact(table, name);  // between two bodies
  const BodyInfo& info = body(table, "body");
  core::Body* b = const_cast<core::Body*>(pose_body(table, "body"));
  components::KikuuweContactParams p;
  p.normal = table.vec3("normal", p.normal);
  const std::optional<Vec3> unit_normal = core::safe_normalized(p.normal);
  if (!unit_normal) table.fail("normal", "must be a non-zero, finite vector");
  p.normal = *unit_normal;
  p.offset = table.number("offset", p.offset);
  p.stiffness = table.positive("stiffness", p.stiffness);
  p.damping = table.non_negative("damping", p.damping);
  const FrictionKeys friction = read_contact_friction(table, p.mu, true);
  p.mu = friction.kinetic;
  p.mu_static = friction.static_level;
  p.stribeck_velocity = friction.stribeck_velocity;
  p.viscous = friction.viscous;
  const FrictionAxes axes = read_friction_axes(table, friction, p.normal, *info.admittance, *b);
  if (friction.anisotropic()) {
    p.mu_2 = friction.kinetic_2;
    p.body_axes = axes.body;
    // World axes as given; body axes: their direction at t = 0 is the fallback (an axis
    // turned along the normal).
    if (axes.body) {
      core::Vec y(info.admittance->state_size());
      info.admittance->initial_state(y);
      p.friction_axis = b->motion(y).q * axes.first;
    } else {
      p.friction_axis = axes.first;
    }
  }
  if (table.has("tangential_stiffness"))
    p.tangential_stiffness = table.positive("tangential_stiffness", 0.0);
  if (table.has("tangential_damping"))
    p.tangential_damping = table.non_negative("tangential_damping", 0.0);
  p.extent = read_extent(table, p.normal, p.offset);

  // The body points: a list, a box's corners, or the one point p - radius n.
  std::vector<Vec3> points;
  const bool listed = table.has("points");
  if (listed) {
    const toml::node* node = table.node("points");
    const toml::array* a = node->as_array();
    if (a == nullptr || a->empty())
      table.fail("points", "expected a non-empty array of [x, y, z] points");
    // Refused before anything is allocated: each point is an element with 9 output columns,
    // events and a summary entry, about 51 kB of a run's memory (docs/limits.md); 100000 points
    // ended in std::bad_alloc (issue 25).
    if (a->size() > kMaxContactPoints) {
      char estimate[64];
      std::snprintf(estimate, sizeof estimate, "%.1f GB",
                    static_cast<double>(a->size()) * kBytesPerContactPoint / 1e9);
      table.fail("points", std::to_string(a->size()) + " contact points would need about " +
                               estimate + " (about " +
                               std::to_string(static_cast<int>(kBytesPerContactPoint / 1000)) +
                               " kB each); the limit is " + std::to_string(kMaxContactPoints) +
                               " points per contact (docs/limits.md)");
    }
    for (const toml::node& e : *a) {
      const toml::array* xyz = e.as_array();
      bool ok = xyz != nullptr && xyz->size() == 3;
      Vec3 v = Vec3::Zero();
      for (std::size_t i = 0; ok && i < 3; ++i) {
        ok = (*xyz)[i].is_number();
        if (ok) v[static_cast<int>(i)] = finite_number((*xyz)[i], table.path() + ".points");
      }
      if (!ok)
        throw InputError::at(e.source(),
                             table.path() + ".points: expected [x, y, z] (finite numbers)");
      points.push_back(v);
    }
    if (!b->can_rotate() && points.size() > 1) {
      table.fail("points", "a point_mass has one point (its position): several need a rigid_body");
    }
  } else if (info.box_size != Vec3::Zero()) {
    const Vec3 h = 0.5 * info.box_size;
    for (int i = 0; i < 8; ++i) {
      points.emplace_back((i & 1 ? 1 : -1) * h.x(), (i & 2 ? 1 : -1) * h.y(),
                          (i & 4 ? 1 : -1) * h.z());
    }
  } else if (info.cylinder) {
    points.assign(components::CylinderRimMap::kPoints, Vec3::Zero());  // rim points: the map's
  } else {
    points.emplace_back(Vec3::Zero());
  }
  const bool rim = info.cylinder && !listed;
  if (rim && table.has("radius"))
    table.fail("radius", "a cylinder's contact points are on its rims (no rounding radius)");
  const bool several = listed || points.size() > 1;
  const double radius = table.non_negative("radius", several ? 0.0 : info.sphere_radius);

  // Friction state at t = 0: one [e0, e1] for every point, or one per point.
  std::vector<Eigen::Vector2d> initial_e(points.size(), Eigen::Vector2d::Zero());
  if (const toml::node* node = table.node("initial_e")) {
    const toml::array* a = node->as_array();
    auto pair = [&](const toml::node& n) -> std::optional<Eigen::Vector2d> {
      const toml::array* e = n.as_array();
      if (e == nullptr || e->size() != 2 || !(*e)[0].is_number() || !(*e)[1].is_number())
        return std::nullopt;
      const std::string what = table.path() + ".initial_e";
      const Eigen::Vector2d v(finite_number((*e)[0], what), finite_number((*e)[1], what));
      if (!v.allFinite()) return std::nullopt;
      return v;
    };
    if (a != nullptr && pair(*node)) {
      std::fill(initial_e.begin(), initial_e.end(), *pair(*node));
    } else if (a != nullptr && a->size() == points.size() &&
               std::all_of(a->begin(), a->end(),
                           [&](const toml::node& n) { return pair(n).has_value(); })) {
      for (std::size_t i = 0; i < points.size(); ++i) initial_e[i] = *pair((*a)[i]);
    } else {
      table.fail(
          "initial_e",
          "expected [e0, e1] (m, along the surface's tangents) or one such pair per point (" +
              std::to_string(points.size()) + ")");
    }
  }

  // A moving surface: a belt and/or a tilt, each a number or an expression of t.
  components::SurfaceMotion motion;
  if (table.has("belt_speed")) {
    motion.belt_speed = time_profile(table, "belt_speed");
    const Vec3 d = table.vec3("belt_direction", Vec3::UnitX());
    if (!((d - p.normal.dot(d) * p.normal).norm() > 1e-9 * std::max(1.0, d.norm()))) {
      table.fail("belt_direction",
                 "must be a direction in the surface plane (not along the normal)");
    }
    motion.belt_direction = d;
  } else if (table.has("belt_direction")) {
    table.fail("belt_direction", "needs `belt_speed`");
  }
  if (table.has("tilt")) {
    motion.tilt = time_profile(table, "tilt");
    motion.tilt_axis = table.vec3("tilt_axis", motion.tilt_axis);
    const std::optional<Vec3> unit_axis = core::safe_normalized(motion.tilt_axis);
    if (!unit_axis) table.fail("tilt_axis", "must be a non-zero, finite vector");
    motion.tilt_axis = *unit_axis;
    motion.pivot = table.vec3("tilt_pivot", p.offset * p.normal);
  } else {
    for (const char* key : {"tilt_axis", "tilt_pivot"}) {
      if (table.has(key)) table.fail(key, "needs `tilt`");
    }
  }
  const bool moving = static_cast<bool>(motion.belt_speed) || static_cast<bool>(motion.tilt);
  const bool settle = table.boolean("settle", false);
  const double threshold = table.positive("stick_threshold", 1e-3);
  if (rim) reject_for_cylinder(table, moving, settle);
  if (p.body_axes && (moving || rim)) {
    table.fail("friction_axes_frame",
               moving ? "body-fixed axes need a fixed surface (no `belt_speed` or `tilt`)"
                      : "body-fixed axes are not supported for a cylinder's rim contacts yet "
                        "(use \"world\")");
  }
  // (A cylinder on a moving surface was refused just above.)
  const std::vector<RollingElement> rolling =
      read_rolling_resistance(table, info.sphere_radius, rim ? &*info.cylinder : nullptr, *b, p,
                              radius, listed || several || moving || rim);
  table.finish();
  count_contact_elements(table, points.size());

  if (moving && clock_ == nullptr) {
    // One clock for every moving surface; its name cannot clash with a component's
    // (those have no '.').
    auto clock = std::make_unique<components::Clock>("scene.clock");
    clock_ = clock.get();
    network_.add_admittance(std::move(clock));
  }
  // What is drawn: the surface (once per table), and where each element acts.
  const int drawn = body_index(drawing_, info.admittance->name());
  SurfaceVisual surface{p.normal.normalized(), p.offset, p.extent, nullptr};
  if (drawn >= 0 &&
      drawing_.bodies[static_cast<std::size_t>(drawn)].kind == BodyVisual::Kind::block) {
    drawing_.bodies[static_cast<std::size_t>(drawn)].up = surface.normal;
  }
  SettleBody* settling = nullptr;
  if (settle) {
    for (auto& s : settle_) {
      if (s.body == info.admittance) settling = &s;
    }
    if (settling == nullptr) settling = &settle_.emplace_back(SettleBody{info.admittance, {}});
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::string element = several ? name + "." + std::to_string(i) : name;
    p.initial_e = initial_e[i];
    std::unique_ptr<core::Impedance> impedance;
    std::unique_ptr<core::CoordinateMap> map;
    SettlePoint sp;
    ContactSite site;
    site.name = element;
    site.group = name;
    site.body = drawn;
    site.normal = surface.normal;
    site.offset = p.offset;
    if (rim) {
      site.rule = ContactSite::Rule::rim;
      site.rim =
          core::RimPoint::leg(info.cylinder->radius, info.cylinder->length, info.cylinder->axis,
                              info.cylinder->radial(), static_cast<int>(i));
    } else {
      site.local = points[i];
      site.radius = radius;
    }
    // A trail under a single point, and under a wheel's nearest rim point on each cap.
    site.trail = !several || (rim && i % 3 == 0);
    if (moving) {
      auto contact = construct_contact(table, [&] {
        return std::make_unique<components::MovingContact>(element, p, motion, radius);
      });
      const components::SurfaceState at0 = contact->surface(0.0);
      sp.frame = at0.frame;
      sp.origin = at0.origin;
      const components::MovingContact* c = contact.get();
      sp.inside = [c](const Vec3& x) {
        const components::SurfaceState s = c->surface(0.0);
        const Vec3 at_rest = c->motion().pivot + s.rotation.conjugate() * (x - c->motion().pivot);
        return !c->params().extent.bounded() ||
               c->params().extent.contains(at_rest - c->params().extent.centre);
      };
      sp.set_e = [c = contact.get()](const Eigen::Vector2d& e) { c->set_initial_e(e); };
      site.moving = contact.get();
      if (surface.moving == nullptr) surface.moving = contact.get();  // the table's first
      impedance = std::move(contact);
      map = std::make_unique<components::SurfacePointMap>(*b, points[i], *clock_);
    } else {
      auto contact = construct_contact(
          table, [&] { return std::make_unique<components::KikuuweContact>(element, p); });
      sp.frame = {contact->normal(), contact->tangent1(), contact->tangent2()};
      sp.origin = p.offset * p.normal;
      const components::SurfaceExtent extent = p.extent;
      sp.inside = [extent](const Vec3& x) {
        return !extent.bounded() || extent.contains(x - extent.centre);
      };
      sp.set_e = [c = contact.get()](const Eigen::Vector2d& e) { c->set_initial_e(e); };
      impedance = std::move(contact);
      if (rim) {
        map = std::make_unique<components::CylinderRimMap>(*b, *info.cylinder, p.normal,
                                                           static_cast<int>(i));
      } else {
        auto point = std::make_unique<components::ContactPointMap>(*b, radius, p.normal, points[i]);
        if (p.body_axes) point->carry_axis(axes.first);
        map = std::move(point);
      }
    }
    if (settling != nullptr) {
      sp.local = points[i];
      sp.radius = radius;
      sp.k = p.stiffness;
      sp.kt = p.tangential_stiffness > 0.0 ? p.tangential_stiffness : p.stiffness;
      settling->points.push_back(std::move(sp));
    }
    stick_thresholds_[element] = threshold;
    impedance_types_.emplace(element, "kikuuwe_contact");
    add_element(std::move(impedance), std::move(map));
    drawing_.sites.contacts.push_back(std::move(site));
  }
  // Rolling and spinning resistance (a sphere or a cylinder on a fixed plane): NAME.rolling,
  // NAME.spin.
  for (const RollingElement& r : rolling) {
    const std::string element = name + "." + r.suffix;
    auto resistance = construct_contact(table, [&] {
      return std::make_unique<components::RollingResistance>(element, p, r.params);
    });
    stick_thresholds_[element] = threshold;
    impedance_types_.emplace(element, "kikuuwe_contact");
    std::unique_ptr<core::CoordinateMap> map;
    if (r.params.body == components::RollingBody::cylinder) {
      map = std::make_unique<components::CylinderTwistMap>(*b, *info.cylinder, p.normal);
    } else {
      map = std::make_unique<components::BodyTwistMap>(*b);
    }
    add_element(std::move(resistance), std::move(map));
  }
  add_surface(drawing_, surface);
  // The table's own name too, so no other component takes it.
  impedance_types_.emplace(name, "kikuuwe_contact");
}

void ComponentBuilder::finish() {
  wire_sources();
  for (Pending& p : pending_) network_.add_impedance(std::move(p.impedance), std::move(p.map));
  pending_.clear();
  for (const SettleBody& s : settle_) settle(s, gravity_);
}

}  // namespace stiction::scene
