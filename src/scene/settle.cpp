#include "scene/settle.hpp"

#include <Eigen/QR>

#include "components/admittance/point_mass.hpp"
#include "components/admittance/rigid_body.hpp"

namespace stiction::scene {

using core::Vec3;

namespace {

constexpr double kTouch = 1e-6;  // m: points this close above a surface carry load

Eigen::Matrix3d skew(const Vec3& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

}  // namespace

void settle(const SettleBody& b, const Vec3& gravity) {
  auto* rigid = dynamic_cast<components::RigidBody*>(b.body);
  auto* point = dynamic_cast<components::PointMass*>(b.body);
  if (rigid == nullptr && point == nullptr) return;
  const double mass = rigid ? rigid->params().mass : point->params().mass;
  Vec3 p = rigid ? rigid->params().position : point->params().position;
  core::Quat q = rigid ? rigid->params().orientation : core::Quat::Identity();

  auto lever = [&](const SettlePoint& s, const core::Quat& at) {
    return Vec3((rigid ? at * s.local : s.local) - s.radius * s.frame.n);
  };
  // The touching points, and where each one is before loading (its friction anchor).
  std::vector<const SettlePoint*> touching;
  std::vector<Vec3> anchor;
  for (const SettlePoint& s : b.points) {
    const Vec3 c = p + lever(s, q);
    if (s.frame.n.dot(s.origin - c) >= -kTouch && s.inside(c)) {
      touching.push_back(&s);
      anchor.push_back(c);
    }
  }
  if (touching.empty()) return;

  const int dof = rigid ? 6 : 3;
  auto forces = [&](const Vec3& at_p, const core::Quat& at_q, Eigen::Matrix<double, 6, 1>& residual,
                    Eigen::Matrix<double, 6, 6>& stiffness) {
    residual.setZero();
    stiffness.setZero();
    residual.head<3>() = mass * gravity;
    for (std::size_t i = 0; i < touching.size(); ++i) {
      const SettlePoint& s = *touching[i];
      const Vec3& n = s.frame.n;
      const Vec3 r = lever(s, at_q);
      const Vec3 c = at_p + r;
      const Vec3 slide = c - anchor[i] - n.dot(c - anchor[i]) * n;
      const Vec3 f = s.k * n.dot(s.origin - c) * n - s.kt * slide;  // stuck, at rest
      residual.head<3>() += f;
      residual.tail<3>() += r.cross(f);
      const Eigen::Matrix3d S =
          s.k * n * n.transpose() + s.kt * (Eigen::Matrix3d::Identity() - n * n.transpose());
      Eigen::Matrix<double, 3, 6> A;
      A << Eigen::Matrix3d::Identity(), -skew(r);  // dc = dp + dtheta x r
      stiffness += A.transpose() * S * A;
    }
  };
  for (int iteration = 0; iteration < 8; ++iteration) {
    Eigen::Matrix<double, 6, 1> residual;
    Eigen::Matrix<double, 6, 6> stiffness;
    forces(p, q, residual, stiffness);
    // stiffness * step = residual: the springs' change of force cancels what is left over.
    const Eigen::VectorXd step =
        stiffness.topLeftCorner(dof, dof).completeOrthogonalDecomposition().solve(
            residual.head(dof));
    p += step.head<3>();
    if (rigid) {
      const Vec3 dtheta = step.tail<3>();
      if (dtheta.norm() > 0.0)
        q = core::Quat(Eigen::AngleAxisd(dtheta.norm(), dtheta.normalized())) * q;
      q.normalize();
    }
    if (step.norm() < 1e-15) break;
  }
  if (rigid)
    rigid->set_initial_pose(p, q);
  else
    point->set_initial_position(p);
  for (std::size_t i = 0; i < touching.size(); ++i) {
    const SettlePoint& s = *touching[i];
    const Vec3 slide = p + lever(s, q) - anchor[i];
    s.set_e(Eigen::Vector2d(s.frame.t1.dot(slide), s.frame.t2.dot(slide)));
  }
}

}  // namespace stiction::scene
