// Where a flat contact surface exists: the rectangle [u_min, u_max] x [v_min, v_max] of its
// own plane, in coordinates along `u` and `v = normal x u` from `centre`. Infinite bounds
// give half-planes and strips (a slope that ends where a floor begins); the default is the
// whole plane. Points outside the extent are not in contact with the surface.
#pragma once

#include <cmath>
#include <limits>

#include "core/types.hpp"

namespace stiction::components {

struct SurfaceExtent {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  core::Vec3 centre = core::Vec3::Zero();  // a point of the plane (world, surface frame at rest)
  core::Vec3 u = core::Vec3::UnitX();      // unit, in the plane
  core::Vec3 v = core::Vec3::UnitY();      // unit, normal x u
  double u_min = -kInf, u_max = kInf, v_min = -kInf, v_max = kInf;

  bool bounded() const {
    return std::isfinite(u_min) || std::isfinite(u_max) || std::isfinite(v_min) ||
           std::isfinite(v_max);
  }
  // `d` is the point minus `centre`, both in the same frame as u and v.
  bool contains(const core::Vec3& d) const {
    const double a = u.dot(d), b = v.dot(d);
    return a >= u_min && a <= u_max && b >= v_min && b <= v_max;
  }
};

}  // namespace stiction::components
