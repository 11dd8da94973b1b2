// Psi/Phi for one contact point of a cylinder (or ring) against a flat surface of normal n.
// A cylinder touches a plane only on its two rim circles (they span its convex hull), so
// each end cap carries a "tripod" of three rim points at angles phi*, phi* + 120 deg and
// phi* + 240 deg about the axis, where phi* points at the rim point nearest the surface:
// the in-cap direction of -n. Rolling on the rim: the phi* point of each cap touches (a line
// contact as two points). Tilted on an edge: one phi* point (a rolling coin precesses).
// Flat on a face: all three points of the lower cap touch (a stable support).
// When the caps are parallel to the surface the in-cap direction of -n vanishes; the map
// then leans towards a fixed body-frame radial direction r, d = d_perp + blend (1 -
// |d_perp| / blend)^2 R r (blend = 1e-3: the lean is zero beyond that tilt, so on the rim the
// points are exactly the lowest ones), and the points follow the body continuously when flat.
// The price: near |d_perp| = 0.38 blend on the side opposite r the direction turns quickly
// (any continuous choice has such a point: the in-cap direction of -n has winding number one
// around "flat"); at such a small tilt the tripod's points are all within r blend of the plane.
// x_hat = [p_c (3), v_c (3)]: the rim point's position and the velocity of the material
// point there, v + w x (p_c - p), so pure rolling gives zero slip as for a sphere. The body
// receives -u at p_c (force and the matching torque).
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"
#include "core/rim_point.hpp"

namespace stiction::components {

// A cylinder in its body frame: centred on the origin (the centre of mass), `axis` a unit
// vector; `radial` a unit body-frame vector normal to the axis (the flat-face tripod's
// leg direction).
struct CylinderShape {
  double radius = 0.0;
  double length = 0.0;
  core::Vec3 axis{0.0, 0.0, 1.0};
  bool hollow = false;
  core::Vec3 radial() const;
};

class CylinderRimMap final : public core::CoordinateMap {
 public:
  static constexpr int kPoints = core::RimPoint::kPoints;  // 0-2 on the +axis cap, 3-5 on the -axis cap
  static constexpr double kBlend = core::RimPoint::kBlend;

  // `index` in 0..kPoints-1.
  CylinderRimMap(const core::Body& body, const CylinderShape& shape, const core::Vec3& normal,
                 int index);
  int motion_size() const override { return 6; }
  int force_size() const override { return 3; }
  std::vector<const core::Admittance*> admittances() const override { return {&body_}; }
  void bind(const std::vector<core::Slot>& slots) override { slot_ = slots.at(0); }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  // The rim point nearest the plane travels over the rim as the cylinder rolls.
  std::optional<ContactSite> contact_site(core::ConstVecRef x) const override {
    Eigen::Matrix<double, 6, 1> x_hat;
    motion(x, x_hat);
    return ContactSite{x_hat.head<3>(), true};
  }
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;

  // The rim point minus the body origin, world frame, for a body at orientation q.
  core::Vec3 lever(const core::Quat& q) const { return rim_.lever(q, normal_); }

 private:
  const core::Body& body_;
  core::Vec3 normal_;
  core::RimPoint rim_;  // the geometry, shared with the drawing (core/rim_point.hpp)
  core::Slot slot_;
};

}  // namespace stiction::components
