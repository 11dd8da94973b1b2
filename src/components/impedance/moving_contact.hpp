// Kikuuwe contact (contact_law.hpp) against a flat surface that moves with time: a belt (the
// surface material moves along the plane at a prescribed speed, the plane stays) and/or a
// plane tilted by a prescribed angle about an axis through a pivot. The friction element
// sees the contact point's velocity relative to the surface material, so a belt drags a
// body along and a tilting plane carries it.
// Input x_hat = [p_b (3), v_b (3), w (3), s (1)]: the world position and velocity of a body
// point (the centre of the contact sphere), the body's world angular velocity, and the
// time s (a Clock's state, surface_point_map.hpp). The contact point is p_b - radius n(s).
// Output u = -[force on the body at the contact point (3), its torque about p_b (3)].
// A moving surface is an energy source: power_in is the surface's power on the body.
// Signals as a fixed contact's (f, slip relative to the surface, e, n_force), plus `angle`
// (the tilt, rad) when tilted and `belt_speed` (m/s) with a belt.
#pragma once

#include <functional>

#include "components/impedance/contact_law.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "core/contact.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

struct SurfaceMotion {
  using Profile = std::function<double(double)>;
  Profile tilt;                                     // angle (rad) of t; empty: not tilted
  core::Vec3 tilt_axis = core::Vec3::UnitY();       // world, unit
  core::Vec3 pivot = core::Vec3::Zero();            // a point of the axis (world)
  Profile belt_speed;                               // m/s of t along belt_direction; empty: no belt
  core::Vec3 belt_direction = core::Vec3::UnitX();  // in the plane at rest (projected, unit)
};

// The surface at time s: its frame and the velocity of its material at a world point.
struct SurfaceState {
  ContactFrame frame;
  core::Vec3 origin;  // a point of the plane (the rest plane's offset * n, moved)
  core::Quat rotation = core::Quat::Identity();  // rest plane -> plane at s
  core::Vec3 omega = core::Vec3::Zero();         // angular velocity (world)
  core::Vec3 belt = core::Vec3::Zero();          // belt velocity (world)
  double angle = 0.0, speed = 0.0;
};

class MovingContact final : public core::Impedance,
                            public ContactCapabilities,
                            public core::Source {
 public:
  MovingContact(std::string name, const KikuuweContactParams& params, const SurfaceMotion& motion,
                double radius);
  std::string_view type() const override { return "kikuuwe_contact"; }
  int input_size() const override { return 10; }
  int output_size() const override { return 6; }
  int state_size() const override { return 2; }
  std::vector<std::string> state_labels() const override { return {"e.0", "e.1"}; }
  void initial_state(core::VecRef y) const override { y.head<2>() = params_.initial_e; }
  void set_initial_e(const Eigen::Vector2d& e) { params_.initial_e = e; }
  void evaluate(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau, core::VecRef u,
                core::VecRef y_dot) const override;
  std::vector<core::SignalInfo> signals() const override;
  void write_signals(core::ConstVecRef x_hat, core::ConstVecRef y, core::ConstVecRef u,
                     core::VecRef out) const override;
  int regime(core::ConstVecRef x_hat, core::ConstVecRef y, double tau) const override;
  double stored_energy(core::ConstVecRef x_hat, core::ConstVecRef y) const override;
  core::Vec3 slip_velocity(core::ConstVecRef x_hat) const override;
  core::Vec3 unloaded_slip(core::ConstVecRef x_hat, core::ConstVecRef y,
                           double tau) const override;
  void evaluate_friction_held(double t, core::ConstVecRef x_hat, core::ConstVecRef y, double tau,
                              core::ConstVecRef u_ref, core::ConstVecRef y_dot_ref, core::VecRef u,
                              core::VecRef y_dot) const override;
  // The power the moving surface gives the body (a source: the surface's motion is prescribed).
  double power_in(core::ConstVecRef x_hat, core::ConstVecRef u) const override;
  // Open while the point is off the surface or outside its extent: no stick or slip events.
  double contact_normal_force(core::ConstVecRef x_hat) const override {
    return normal_force(touch(x_hat));
  }
  double contact_closure(core::ConstVecRef x_hat) const override;

  SurfaceState surface(double s) const;
  // Distance the belt has moved by time s (integral of its speed; 0 without a belt), for
  // drawing its texture.
  double belt_travel(double s) const;
  const KikuuweContactParams& params() const { return params_; }
  const SurfaceMotion& motion() const { return motion_; }
  double radius() const { return radius_; }
  // The belt's direction on the plane at rest (unit).
  const core::Vec3& belt_direction() const { return belt_direction_; }

 private:
  // The contact point's geometry at x_hat: world point, its velocity relative to the surface
  // material, penetration, and whether it lies within the extent.
  struct Touch {
    SurfaceState surface;
    core::Vec3 point, lever, v_rel;
    double depth;
    bool inside;
  };
  Touch touch(core::ConstVecRef x_hat) const;
  double normal_force(const Touch& c) const;

  KikuuweContactParams params_;
  SurfaceMotion motion_;
  double radius_;
  ContactFrame rest_;  // the frame at rest (no tilt)
  ContactCoefficients coefficients_;
  core::Vec3 belt_direction_;
};

}  // namespace stiction::components
