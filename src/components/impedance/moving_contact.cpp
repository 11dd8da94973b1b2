#include "components/impedance/moving_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace stiction::components {

using core::ConstVecRef;
using core::Vec3;
using core::VecRef;

MovingContact::MovingContact(std::string name, const KikuuweContactParams& params,
                             const SurfaceMotion& motion, double radius)
    : Impedance(std::move(name)),
      ContactCapabilities(
          params.stiffness, params.damping, std::max({params.mu, params.mu_static, params.mu_2}),
          params.tangential_stiffness > 0.0 ? params.tangential_stiffness : params.stiffness,
          static_to_kinetic(params.mu, params.mu_static)),
      params_(params),
      motion_(motion),
      radius_(radius) {
  // The fixed contact checks the parameters and builds the rest frame the same way.
  const KikuuweContact fixed("rest", params_);
  rest_ = {fixed.normal(), fixed.tangent1(), fixed.tangent2()};
  coefficients_ = {
      params_.stiffness, params_.damping,
      params_.tangential_stiffness > 0.0 ? params_.tangential_stiffness : params_.stiffness,
      params_.tangential_damping >= 0.0 ? params_.tangential_damping : params_.damping,
      fixed.friction()};  // an anisotropic law's axis turns with the surface's frame
  if (params_.body_axes) {
    throw std::invalid_argument("contact: body-fixed friction axes need a fixed surface");
  }
  if (!(radius_ >= 0.0)) throw std::invalid_argument("contact: radius must be >= 0");
  if (motion_.tilt && !(motion_.tilt_axis.norm() > 0.0))
    throw std::invalid_argument("contact: zero tilt axis");
  motion_.tilt_axis.normalize();
  const Vec3 d = motion_.belt_direction - rest_.n.dot(motion_.belt_direction) * rest_.n;
  if (motion_.belt_speed && !(d.norm() > 1e-9)) {
    throw std::invalid_argument("contact: the belt direction must not be along the normal");
  }
  belt_direction_ = d.norm() > 1e-9 ? Vec3(d.normalized()) : rest_.t1;
}

SurfaceState MovingContact::surface(double s) const {
  SurfaceState st;
  if (motion_.tilt) {
    st.angle = motion_.tilt(s);
    // The tilt rate by a central difference: the profile is any expression of t.
    const double h = 1e-6 * (1.0 + std::abs(s));
    const double rate = (motion_.tilt(s + h) - motion_.tilt(s - h)) / (2.0 * h);
    st.rotation = core::Quat(Eigen::AngleAxisd(st.angle, motion_.tilt_axis));
    st.omega = rate * motion_.tilt_axis;
  }
  st.frame = {st.rotation * rest_.n, st.rotation * rest_.t1, st.rotation * rest_.t2};
  st.origin = motion_.pivot + st.rotation * (params_.offset * rest_.n - motion_.pivot);
  if (motion_.belt_speed) {
    st.speed = motion_.belt_speed(s);
    st.belt = st.speed * (st.rotation * belt_direction_);
  }
  return st;
}

double MovingContact::belt_travel(double s) const {
  if (!motion_.belt_speed || s <= 0.0) return 0.0;
  // Composite Simpson with steps of at most 1 ms: smooth profiles come out exact enough to
  // draw, a switch costs at most one step's error.
  const int n = 2 * std::max(8, static_cast<int>(std::ceil(s / 2e-3)));
  const double h = s / n;
  double sum = motion_.belt_speed(0.0) + motion_.belt_speed(s);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * motion_.belt_speed(i * h);
  return sum * h / 3.0;
}

MovingContact::Touch MovingContact::touch(ConstVecRef x_hat) const {
  Touch c;
  c.surface = surface(x_hat[9]);
  const Vec3& n = c.surface.frame.n;
  const Vec3 p_b = x_hat.segment<3>(0);
  const Vec3 w = x_hat.segment<3>(6);
  c.lever = -radius_ * n;
  c.point = p_b + c.lever;
  const Vec3 v_c = Vec3(x_hat.segment<3>(3)) + w.cross(c.lever);
  const Vec3 v_surface = c.surface.omega.cross(c.point - motion_.pivot) + c.surface.belt;
  c.v_rel = v_c - v_surface;
  c.depth = n.dot(c.surface.origin - c.point);
  // The extent is given on the plane at rest: carry the point back there.
  const Vec3 at_rest = motion_.pivot + c.surface.rotation.conjugate() * (c.point - motion_.pivot);
  c.inside = !params_.extent.bounded() || params_.extent.contains(at_rest - params_.extent.centre);
  return c;
}

double MovingContact::normal_force(const Touch& c) const {
  return c.inside ? components::contact_normal_force(coefficients_, c.depth,
                                                     c.surface.frame.n.dot(c.v_rel))
                  : 0.0;
}

double MovingContact::contact_closure(ConstVecRef x_hat) const {
  const Touch c = touch(x_hat);
  return c.inside ? components::contact_closure(coefficients_, c.depth,
                                                c.surface.frame.n.dot(c.v_rel))
                  : std::numeric_limits<double>::quiet_NaN();
}

void MovingContact::evaluate(double /*t*/, ConstVecRef x_hat, ConstVecRef y, double tau, VecRef u,
                             VecRef y_dot) const {
  const Touch c = touch(x_hat);
  const Vec3 on_body = contact_law(c.surface.frame, coefficients_, normal_force(c), c.v_rel,
                                   y.head<2>(), tau, y_dot.head<2>());
  u.head<3>() = -on_body;
  u.segment<3>(3) = -c.lever.cross(on_body);
}

int MovingContact::regime(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  const Touch c = touch(x_hat);
  if (normal_force(c) == 0.0) return 0;
  Eigen::Matrix<double, 6, 1> u;
  Eigen::Vector2d y_dot;
  evaluate(0.0, x_hat, y, tau, u, y_dot);
  const Eigen::Vector2d v_t(c.surface.frame.t1.dot(c.v_rel), c.surface.frame.t2.dot(c.v_rel));
  return y_dot == v_t ? 1 : 2;
}

void MovingContact::evaluate_friction_held(double /*t*/, ConstVecRef x_hat, ConstVecRef /*y*/,
                                           double /*tau*/, ConstVecRef u_ref, ConstVecRef y_dot_ref,
                                           VecRef u, VecRef y_dot) const {
  const Touch c = touch(x_hat);
  const Vec3& n = c.surface.frame.n;
  const Vec3 held = u_ref.head<3>();
  const Vec3 force = held - n.dot(held) * n - normal_force(c) * n;  // = -(force on the body)
  u.head<3>() = force;
  u.segment<3>(3) = c.lever.cross(force);
  y_dot.head<2>() = y_dot_ref.head<2>();
}

Vec3 MovingContact::slip_velocity(ConstVecRef x_hat) const {
  const Touch c = touch(x_hat);
  const Vec3& n = c.surface.frame.n;
  return c.v_rel - n.dot(c.v_rel) * n;
}

Vec3 MovingContact::unloaded_slip(ConstVecRef x_hat, ConstVecRef y, double tau) const {
  const ContactFrame& f = touch(x_hat).surface.frame;
  const double kt = coefficients_.kt;
  return -kt / (coefficients_.bt + tau * kt) * (y[0] * f.t1 + y[1] * f.t2);
}

double MovingContact::stored_energy(ConstVecRef x_hat, ConstVecRef y) const {
  const Touch c = touch(x_hat);
  const double depth = c.inside ? std::max(0.0, c.depth) : 0.0;
  return 0.5 * params_.stiffness * depth * depth +
         0.5 * coefficients_.kt * y.head<2>().squaredNorm();
}

double MovingContact::power_in(ConstVecRef x_hat, ConstVecRef u) const {
  // The surface's material moves at v_surface under the contact point: the power it gives
  // the body is the force on the body times that velocity.
  const Touch c = touch(x_hat);
  const Vec3 v_surface = c.surface.omega.cross(c.point - motion_.pivot) + c.surface.belt;
  return -Vec3(u.head<3>()).dot(v_surface);
}

std::vector<core::SignalInfo> MovingContact::signals() const {
  std::vector<core::SignalInfo> out{
      {.name = "f",
       .axes = core::xyz_axes(),
       .unit = "N",
       .frame = "world",
       .description = "contact force on the body (normal plus friction)"},
      {.name = "slip",
       .axes = core::xyz_axes(),
       .unit = "m/s",
       .frame = "world",
       .description = "velocity of the contact point relative to the moving surface"},
      {.name = "e",
       .axes = core::index_axes(2),
       .unit = "m",
       .frame = "surface",
       .description = "elastic displacement of the tangential friction element"},
      {.name = "n_force", .unit = "N", .description = "normal force magnitude"}};
  if (motion_.tilt) {
    out.push_back({.name = "angle", .unit = "rad", .description = "tilt of the surface"});
  }
  if (motion_.belt_speed) {
    out.push_back({.name = "belt_speed", .unit = "m/s", .description = "speed of the belt"});
  }
  return out;
}

void MovingContact::write_signals(ConstVecRef x_hat, ConstVecRef y, ConstVecRef u,
                                  VecRef out) const {
  const Touch c = touch(x_hat);
  const Vec3& n = c.surface.frame.n;
  const Vec3 on_body = -u.head<3>();
  out.segment<3>(0) = on_body;
  out.segment<3>(3) = c.v_rel - n.dot(c.v_rel) * n;
  out.segment<2>(6) = y.head<2>();
  out[8] = n.dot(on_body);
  int k = 9;
  if (motion_.tilt) out[k++] = c.surface.angle;
  if (motion_.belt_speed) out[k++] = c.surface.speed;
}

}  // namespace stiction::components
