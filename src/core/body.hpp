// Kinematic views of admittances that coordinate maps need. A Body has a pose (point mass,
// rigid body); a JointSpace has generalized joint coordinates (planar arm). Maps use these
// to compute x_hat (Psi) and to turn impedance outputs into admittance inputs (Phi).
#pragma once

#include <string>

#include "core/admittance.hpp"

namespace stiction::core {

struct BodyMotion {
  Vec3 p = Vec3::Zero();          // position of the body frame origin (centre of mass)
  Quat q = Quat::Identity();      // orientation, body to world
  Vec3 v = Vec3::Zero();          // linear velocity of the origin, world frame
  Vec3 w_world = Vec3::Zero();    // angular velocity, world frame

  Vec3 point(const Vec3& local) const { return p + q * local; }
  Vec3 point_velocity(const Vec3& world_point) const { return v + w_world.cross(world_point - p); }
};

class Body : public Admittance {
 public:
  using Admittance::Admittance;
  virtual BodyMotion motion(ConstVecRef x) const = 0;
  // Add a world-frame force applied at `lever` from the body origin (world frame), plus a
  // free world-frame torque, to the body in the configuration `at` (its motion() at the
  // state in question: Phi reuses what Psi computed). A lever rather than a point:
  // (p + a) - p is not a in floating point, and the maps know the lever already.
  virtual void add_wrench(const BodyMotion& at, const Vec3& lever, const Vec3& force,
                          const Vec3& torque, VecRef u_hat) const = 0;
  virtual bool can_rotate() const = 0;
};

class JointSpace : public Admittance {
 public:
  using Admittance::Admittance;
  virtual int joint_count() const = 0;
  virtual double joint_angle(ConstVecRef x, int joint) const = 0;
  virtual double joint_rate(ConstVecRef x, int joint) const = 0;
  virtual void add_joint_torque(int joint, double torque, VecRef u_hat) const = 0;
  // The joint's name, by which a scene may name it (`joint = "NAME"`); empty: the joints
  // are known by index only.
  virtual std::string joint_name(int /*joint*/) const { return {}; }
};

}  // namespace stiction::core
