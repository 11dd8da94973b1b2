// Psi/Phi for a contact between two bodies (PairContact): x_hat = [d (1), n (3), v_rel (3)]
// with the penetration d, the unit normal n along which the first body is pushed, and the
// velocity of the first body's material point at the contact point relative to the
// second's. Phi applies -u (the force on the first body) to the first body and +u to the
// second, each at its own lever to the same contact point, so the pair's forces and moments
// cancel (momentum and angular momentum are kept to rounding).
//
// The geometry (probe_pair) is a free function of the two poses, so the renderer draws the
// forces where the simulation applies them:
// - sphere-sphere: n along the line of centres, d = r_a + r_b - |p_a - p_b|;
// - sphere-box (either order): the box point closest to the centre (box frame, clamped to
//   the half sizes); a centre inside the box is pushed out through the face it is least
//   deep under;
// - box-box: one element per corner (the first box's 8, then the second's 8). The pair's
//   normal is the face axis of least overlap among the six face normals of the two boxes
//   (a separating-axis test on face axes only): when it is a face of the second box, the
//   first box's corners that lie over that face (in its outline) touch it and the second
//   box's corners are open; the other way round when it is a face of the first box. Why not
//   each corner against the face it is least deep under: a corner of a box stacked exactly
//   on an equal box lies on the lower box's edge, as deep under its side face (zero) as
//   under its top, and would be pushed sideways or not at all; the pair's axis sees the
//   stack as a top face. Exactly stacked equal boxes (a tie between the two top/bottom
//   faces) take the second box's face: the first box's four corners carry the load, not
//   eight (no doubled stiffness). A box tipped over the other's edge has its own face as
//   the axis of least overlap, and the other box's corners on that edge push it.
// The contact point is midway between the two surfaces along n.
#pragma once

#include "core/body.hpp"
#include "core/coordinate_map.hpp"

namespace stiction::components {

enum class PairKind { sphere_sphere, sphere_box, box_sphere, box_box };

struct PairShape {
  PairKind kind = PairKind::sphere_sphere;
  double radius_a = 0.0, radius_b = 0.0;                                // spheres
  core::Vec3 half_a = core::Vec3::Zero(), half_b = core::Vec3::Zero();  // boxes: half sides
  int corner = 0;  // box_box: 0-7 the first box's corners, 8-15 the second's
};

struct PairProbe {
  double depth = 0.0;                     // > 0 in contact
  core::Vec3 n{0.0, 0.0, 1.0};            // pushes the first body; unit
  core::Vec3 point = core::Vec3::Zero();  // world contact point
};

// Corner i (0-7) of a box of half sides h, in its frame.
core::Vec3 box_corner(const core::Vec3& h, int i);

PairProbe probe_pair(const PairShape& shape, const core::BodyMotion& a, const core::BodyMotion& b);

class PairContactMap final : public core::CoordinateMap {
 public:
  PairContactMap(const core::Body& a, const core::Body& b, const PairShape& shape)
      : a_(a), b_(b), shape_(shape) {}
  int motion_size() const override { return 7; }
  int force_size() const override { return 3; }
  int conjugate_velocity_offset() const override { return 4; }  // v_rel
  std::vector<const core::Admittance*> admittances() const override { return {&a_, &b_}; }
  void bind(const std::vector<core::Slot>& slots) override {
    slot_a_ = slots.at(0);
    slot_b_ = slots.at(1);
  }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  // The pair's contact point, a point of both bodies (body events count it for each).
  std::optional<ContactSite> contact_site(core::ConstVecRef x) const override {
    return ContactSite{probe_pair(shape_, motion_a(x), motion_b(x)).point, false};
  }
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override;
  const PairShape& shape() const { return shape_; }

 private:
  core::BodyMotion motion_a(core::ConstVecRef x) const {
    return a_.motion(x.segment(slot_a_.state_offset, slot_a_.state_size));
  }
  core::BodyMotion motion_b(core::ConstVecRef x) const {
    return b_.motion(x.segment(slot_b_.state_offset, slot_b_.state_size));
  }

  const core::Body& a_;
  const core::Body& b_;
  PairShape shape_;
  core::Slot slot_a_, slot_b_;
};

}  // namespace stiction::components
