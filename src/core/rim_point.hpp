// Where a cylinder (or ring) touches a plane: one leg of the "tripod" of rim points on each
// end cap (components/maps/cylinder_rim_map.hpp explains the tripods and the lean). Pure
// geometry of a pose, kept here so that the contact map that applies the force and the
// drawing that shows where it acts (scene/drawing.hpp, read by the renderer) compute the
// same point with the same arithmetic, without the renderer depending on components.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/types.hpp"

namespace stiction::core {

struct RimPoint {
  // The lean towards `radial` fades out beyond this tilt of the caps (cylinder_rim_map.hpp).
  static constexpr double kBlend = 1e-3;
  static constexpr int kPoints = 6;  // three per cap: 0-2 on the +axis cap, 3-5 on the -axis cap

  Vec3 axis{0.0, 0.0, 1.0};    // body frame, unit
  Vec3 radial{1.0, 0.0, 0.0};  // body frame, unit, normal to axis (the flat-face leg direction)
  double radius = 0.0;
  double half_length = 0.0;             // signed: the leg's cap, +L/2 or -L/2 along the axis
  double cos_leg = 1.0, sin_leg = 0.0;  // the leg's angle from the point nearest the plane

  // Leg `index` (0..kPoints-1) of a cylinder of `radius` and `length`.
  static RimPoint leg(double radius, double length, const Vec3& axis, const Vec3& radial,
                      int index) {
    RimPoint r;
    r.axis = axis.normalized();
    r.radial = radial;
    r.radius = radius;
    r.half_length = (index < 3 ? 0.5 : -0.5) * length;
    r.cos_leg = std::cos(2.0 * std::numbers::pi / 3.0 * (index % 3));
    r.sin_leg = std::sin(2.0 * std::numbers::pi / 3.0 * (index % 3));
    return r;
  }

  // The leg's point minus the body origin, world frame, for a body at orientation q over a
  // plane of unit normal `normal` (leg 0 and 3: the rim point nearest the plane).
  Vec3 lever(const Quat& q, const Vec3& normal) const {
    const Vec3 a = q * axis;
    // The in-cap direction of -n (towards the surface), leaning on the body's radial
    // direction so that it stays defined (and continuous) when the caps lie parallel to the
    // surface. The lean fades out as (1 - |d_perp| / kBlend)^2: exactly zero beyond a tilt of
    // kBlend, so a cylinder on its rim touches at its lowest point.
    // Near flat, d_perp is the small difference of two unit vectors: on a plane whose normal
    // is not a world axis it carries ~1e-16 of rounding along a, which the lean scales by
    // 1 / kBlend into the point leaving the cap plane by ~1e-15 m (normal force jitter that
    // kept the implicit integrator's Newton iteration from converging on a coin lying on a
    // tilted plane). Removing its part along a again keeps the point in the cap plane.
    Vec3 d_perp = -normal + normal.dot(a) * a;
    d_perp -= d_perp.dot(a) * a;
    const double fade = std::max(0.0, 1.0 - d_perp.norm() / kBlend);
    const Vec3 u = (d_perp + kBlend * fade * fade * (q * radial)).normalized();
    const Vec3 v = a.cross(u);
    return half_length * a + radius * (cos_leg * u + sin_leg * v);
  }

  // How far the whole cylinder reaches from its centre along the unit world direction `d`
  // (its support function), for a body at orientation q.
  double reach(const Quat& q, const Vec3& d) const {
    const double along = std::abs((q * axis).dot(d));
    return along * std::abs(half_length) + radius * std::sqrt(std::max(0.0, 1.0 - along * along));
  }
};

}  // namespace stiction::core
