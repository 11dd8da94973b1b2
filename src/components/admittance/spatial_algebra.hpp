// Spatial (6-D) vectors in the fixed world frame at the world origin, after Featherstone:
// a motion m = (w, v) is an angular velocity w and the velocity v of the body point that
// is passing through the origin; a force f = (n, f) is a moment n about the origin and a
// force f. Keeping every quantity in one frame means no transforms between links: each
// link's joint axis and inertia are rotated into the world once per evaluation.
#pragma once

#include <Eigen/Core>

#include "core/types.hpp"

namespace stiction::components::spatial {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

inline core::Mat3 skew(const core::Vec3& a) {
  core::Mat3 m;
  m << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return m;
}

// m1 x m2 (the rate of change of m2 carried by a body moving with m1).
inline Vec6 motion_cross(const Vec6& a, const Vec6& b) {
  Vec6 r;
  r.head<3>() = a.head<3>().cross(b.head<3>());
  r.tail<3>() = a.head<3>().cross(b.tail<3>()) + a.tail<3>().cross(b.head<3>());
  return r;
}

// m x* f (the dual cross product, for forces).
inline Vec6 force_cross(const Vec6& m, const Vec6& f) {
  Vec6 r;
  r.head<3>() = m.head<3>().cross(f.head<3>()) + m.tail<3>().cross(f.tail<3>());
  r.tail<3>() = m.head<3>().cross(f.tail<3>());
  return r;
}

// Spatial inertia about the origin of a body of `mass` with centre of mass `c` and
// rotational inertia `Ic` about it (both world): [[Ic - m [c]^2, m [c]], [-m [c], m 1]],
// so that I (w, v) is (angular momentum about the origin, linear momentum).
inline Mat6 inertia_at_origin(double mass, const core::Vec3& c, const core::Mat3& Ic) {
  const core::Mat3 cx = skew(c);
  Mat6 I;
  I.topLeftCorner<3, 3>() = Ic - mass * cx * cx;
  I.topRightCorner<3, 3>() = mass * cx;
  I.bottomLeftCorner<3, 3>() = -mass * cx;
  I.bottomRightCorner<3, 3>() = mass * core::Mat3::Identity();
  return I;
}

}  // namespace stiction::components::spatial
