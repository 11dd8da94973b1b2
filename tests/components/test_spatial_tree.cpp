// SpatialTree (the O(n) articulated-body algorithm in 3-D) on generated cases:
// - against PlanarArm on random parallel-axis arms, n = 1..16, with odd axis directions,
//   bases, out-of-plane offsets, joint-frame yaws and full link inertias: the same joint
//   accelerations to rounding, and the same link positions;
// - against H^-1 (tau - c) from mass_matrix() and bias() on random 3-D trees of revolute
//   and prismatic joints (random parents, axes, rpy origins, full inertias);
// - H and c against the Lagrangian built from finite differences of link_poses() (kinetic
//   energy of each link from its centre's velocity and its angular velocity) and of the
//   potential energy: an independent check of the kinematics, inertias and RNEA;
// - H symmetric positive definite; energy conserved by a free tree under gravity with rk4,
//   its drift falling as dt^4.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "components/admittance/planar_arm.hpp"
#include "components/admittance/spatial_tree.hpp"

using namespace stiction;
using components::SpatialJointType;
using components::SpatialLink;
using components::SpatialTree;
using components::SpatialTreeParams;

namespace {

struct Random {
  std::mt19937 rng;
  explicit Random(unsigned seed) : rng(seed) {}
  double between(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  core::Vec3 vec(double size) { return {between(-size, size), between(-size, size), between(-size, size)}; }
  core::Vec3 unit() {
    core::Vec3 v;
    do v = vec(1.0);
    while (v.norm() < 0.1 || v.norm() > 1.0);
    return v.normalized();
  }
  core::Quat rotation() {
    return core::Quat(Eigen::AngleAxisd(between(-std::numbers::pi, std::numbers::pi), unit()));
  }
  // A physical inertia about the com: principal moments that satisfy the triangle
  // inequality (a real body's), turned by a random rotation.
  core::Mat3 inertia(double mass, double size) {
    const double a = between(0.2, 1.0), b = between(0.2, 1.0), c = between(0.2, 1.0);
    const core::Vec3 principal = mass * size * size * core::Vec3(b + c, a + c, a + b);
    const core::Mat3 R = rotation().toRotationMatrix();
    return R * principal.asDiagonal() * R.transpose();
  }
};

// A random tree of n joints: random parents, joint types, axes, rpy origins, masses,
// centres of mass and full inertias, under random gravity.
SpatialTreeParams random_tree(Random& r, int n) {
  SpatialTreeParams p;
  for (int i = 0; i < n; ++i) {
    SpatialLink l;
    l.joint_name = std::string("j").append(std::to_string(i));
    l.parent = i == 0 ? -1 : static_cast<int>(r.between(-1.0, i - 1e-9));
    l.type = r.between(0, 1) < 0.3 ? SpatialJointType::prismatic : SpatialJointType::revolute;
    l.axis = r.unit() * r.between(0.5, 2.0);  // normalized by the tree
    l.origin = r.vec(0.4);
    l.rotation = r.rotation();
    l.mass = r.between(0.1, 3.0);
    l.com = r.vec(0.3);
    l.inertia = r.inertia(l.mass, r.between(0.03, 0.2));
    p.links.push_back(l);
  }
  p.base_position = r.vec(1.0);
  p.base_orientation = r.rotation();
  p.gravity = r.vec(10.0);
  return p;
}

core::Vec random_vec(Random& r, int n, double size) {
  core::Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = r.between(-size, size);
  return v;
}

double condition(const Eigen::MatrixXd& H) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(H);
  return svd.singularValues()(0) / svd.singularValues()(H.rows() - 1);
}

// Kinetic energy from the link poses alone: central differences along q + s qd give each
// link's angular velocity and its centre's velocity.
double kinetic_from_poses(const SpatialTree& tree, const core::Vec& q, const core::Vec& qd) {
  const double h = 1e-5;
  const auto plus = tree.link_poses(q + h * qd);
  const auto minus = tree.link_poses(q - h * qd);
  double energy = 0.0;
  for (std::size_t i = 0; i < plus.size(); ++i) {
    const SpatialLink& l = tree.params().links[i];
    const core::Vec3 c_plus = plus[i].p + plus[i].q * l.com;
    const core::Vec3 c_minus = minus[i].p + minus[i].q * l.com;
    const core::Vec3 v = (c_plus - c_minus) / (2 * h);
    const Eigen::AngleAxisd turn(plus[i].q * minus[i].q.conjugate());
    const core::Vec3 w = turn.axis() * turn.angle() / (2 * h);  // world angular velocity
    const core::Mat3 R = tree.link_poses(q)[i].q.toRotationMatrix();
    energy += 0.5 * l.mass * v.squaredNorm() + 0.5 * w.dot(R * l.inertia * R.transpose() * w);
  }
  return energy;
}

double potential(const SpatialTree& tree, const core::Vec& q) {
  core::Vec x = core::Vec::Zero(2 * q.size());
  x.head(q.size()) = q;
  return tree.energy(x);
}

}  // namespace

TEST_CASE("spatial tree: equals the planar arm on parallel-axis arms, n = 1..16") {
  Random r(20261202);
  double worst_residual = 0.0, worst_relative = 0.0;
  for (int n = 1; n <= 16; ++n) {
    for (int trial = 0; trial < 3; ++trial) {
      components::PlanarArmParams pa;
      pa.axis = r.unit();
      pa.base = r.vec(1.0);
      pa.gravity = r.vec(10.0);  // its part along the axis loads the bearings only
      SpatialTreeParams st;
      core::Vec3 e1, e2;
      components::arm_plane(pa.axis, e1, e2);
      core::Mat3 plane;
      plane << e1, e2, pa.axis;
      st.base_position = pa.base;
      st.base_orientation = core::Quat(plane);
      st.gravity = pa.gravity;
      core::Vec yaw(n);
      for (int i = 0; i < n; ++i) {
        components::ArmLink a;
        a.length = r.between(0.05, 0.5);
        a.mass = r.between(0.05, 2.0);
        a.com = r.between(-0.2, 1.2) * a.length;
        a.inertia = trial == 2 ? 0.0 : r.between(0.0, 0.02);
        pa.links.push_back(a);
        SpatialLink l;
        l.joint_name = std::string("joint").append(std::to_string(i));
        l.parent = i - 1;
        // Joint i sits at the end of link i-1 (along its x), shifted along the axis, with
        // its frame turned about the axis by yaw_i (so its angle reads theta_i - yaw_i).
        l.origin = core::Vec3(i == 0 ? 0.0 : pa.links[i - 1].length, 0.0, r.between(-0.2, 0.2));
        yaw[i] = r.between(-3.0, 3.0);
        l.rotation = core::Quat(Eigen::AngleAxisd(yaw[i], core::Vec3::UnitZ()));
        l.axis = core::Vec3::UnitZ() * r.between(0.3, 3.0);
        l.mass = a.mass;
        l.com = core::Vec3(a.com, 0.0, r.between(-0.1, 0.1));
        // Izz is the arm's; the rest (moments, products) only loads the bearings.
        const double izz = a.inertia;
        const double ixz = 0.3 * izz * r.between(-1, 1), iyz = 0.3 * izz * r.between(-1, 1);
        const double ixx = r.between(0.02, 0.04), iyy = r.between(0.02, 0.04);
        const double ixy = r.between(-0.01, 0.01);
        l.inertia << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
        st.links.push_back(l);
      }
      const components::PlanarArm arm("arm", pa);
      const SpatialTree tree("tree", st);
      const core::Vec theta = random_vec(r, n, 3.2), omega = random_vec(r, n, 4.0),
                      tau = random_vec(r, n, 2.0);
      core::Vec qdd_arm(n), qdd_tree(n);
      arm.forward_dynamics(theta, omega, tau, qdd_arm);
      tree.forward_dynamics(theta - yaw, omega, tau, qdd_tree);

      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
      core::Vec c = core::Vec::Zero(n);
      arm.dynamics(theta, omega, H, c);
      const double scale = (tau - c).norm() + H.norm() * qdd_arm.norm();
      const double residual = (H * qdd_tree + c - tau).norm() / scale;
      const double relative = (qdd_tree - qdd_arm).norm() / qdd_arm.norm() / condition(H);
      INFO("n = " << n << ", trial " << trial << ": residual " << residual
                  << ", relative difference / cond(H) " << relative);
      CHECK(residual < 1e-13);
      CHECK(relative < 1e-13);
      worst_residual = std::max(worst_residual, residual);
      worst_relative = std::max(worst_relative, relative);

      // The link frames sit at the arm's joints (plus their offsets along the axis).
      const auto poses = tree.link_poses(theta - yaw);
      Eigen::Vector2d joint = Eigen::Vector2d::Zero();
      double phi = 0.0;
      for (int i = 0; i < n; ++i) {
        const core::Vec3 d = poses[i].p - pa.base;
        CHECK((Eigen::Vector2d(d.dot(e1), d.dot(e2)) - joint).norm() < 1e-12);
        phi += theta[i];
        joint += pa.links[i].length * Eigen::Vector2d(std::cos(phi), std::sin(phi));
      }
    }
  }
  INFO("largest residual " << worst_residual << ", relative / cond " << worst_relative);
  CHECK(worst_residual < 1e-13);
}

TEST_CASE("spatial tree: articulated-body dynamics equal H^-1 (tau - c) on random 3-D trees") {
  Random r(7231);
  double worst = 0.0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial % 20;
    const SpatialTree tree("tree", random_tree(r, n));
    const core::Vec q = random_vec(r, n, 3.0), qd = random_vec(r, n, 3.0),
                    tau = random_vec(r, n, 5.0);
    Eigen::MatrixXd H(n, n);
    core::Vec c(n), qdd(n);
    tree.mass_matrix(q, H);
    tree.bias(q, qd, c);
    tree.forward_dynamics(q, qd, tau, qdd);
    CHECK((H - H.transpose()).norm() <= 1e-14 * H.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
    CHECK(eig.eigenvalues().minCoeff() > 0.0);
    const core::Vec reference = H.llt().solve(tau - c);
    const double relative = (qdd - reference).norm() / reference.norm();
    INFO("n = " << n << ": relative difference " << relative << ", cond(H) " << condition(H));
    CHECK(relative < 1e-10);
    worst = std::max(worst, relative);
  }
  INFO("largest relative difference " << worst);
  CHECK(worst < 1e-10);
}

TEST_CASE("spatial tree: H and c agree with the Lagrangian from link poses and potential") {
  Random r(99);
  for (int trial = 0; trial < 12; ++trial) {
    const int n = 1 + trial % 7;
    const SpatialTree tree("tree", random_tree(r, n));
    const core::Vec q = random_vec(r, n, 3.0), qd = random_vec(r, n, 2.0);
    Eigen::MatrixXd H(n, n);
    tree.mass_matrix(q, H);
    const double kinetic = 0.5 * qd.dot(H * qd);
    INFO("n = " << n << ", trial " << trial);
    CHECK(std::abs(kinetic_from_poses(tree, q, qd) - kinetic) <= 1e-8 * kinetic);

    // Lagrange: c = Hdot qd - d/dq (qd^T H qd / 2) + dV/dq, by central differences.
    const double h = 1e-5;
    Eigen::MatrixXd Hp(n, n), Hm(n, n);
    tree.mass_matrix(q + h * qd, Hp);
    tree.mass_matrix(q - h * qd, Hm);
    core::Vec expected = (Hp - Hm) / (2 * h) * qd;
    for (int i = 0; i < n; ++i) {
      const core::Vec dq = core::Vec::Unit(n, i) * h;
      tree.mass_matrix(q + dq, Hp);
      tree.mass_matrix(q - dq, Hm);
      expected[i] += -0.5 * qd.dot((Hp - Hm) * qd) / (2 * h) +
                     (potential(tree, q + dq) - potential(tree, q - dq)) / (2 * h);
    }
    core::Vec c(n);
    tree.bias(q, qd, c);
    CHECK((c - expected).norm() <= 1e-6 * (1.0 + expected.norm()));
  }
}

TEST_CASE("spatial tree: a free tree under gravity keeps its energy with rk4, drift ~ dt^4") {
  Random r(4242);
  for (int trial = 0; trial < 3; ++trial) {
    const int n = 3 + 2 * trial;
    SpatialTreeParams p = random_tree(r, n);
    p.angles = random_vec(r, n, 1.0);
    p.rates = random_vec(r, n, 1.0);
    const SpatialTree tree("tree", p);
    const core::Vec zero = core::Vec::Zero(n);
    auto drift = [&](double dt) {
      core::Vec x(2 * n), k1(2 * n), k2(2 * n), k3(2 * n), k4(2 * n);
      tree.initial_state(x);
      const double e0 = tree.energy(x);
      double worst = 0.0;
      for (int step = 0; step < static_cast<int>(std::lround(0.5 / dt)); ++step) {
        tree.derivative(x, zero, k1);
        tree.derivative(x + 0.5 * dt * k1, zero, k2);
        tree.derivative(x + 0.5 * dt * k2, zero, k3);
        tree.derivative(x + dt * k3, zero, k4);
        x += dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
        worst = std::max(worst, std::abs(tree.energy(x) - e0));
      }
      return worst;
    };
    // Energy scale: the kinetic energy plus the potential range of the tree's masses.
    double scale = 0.0;
    for (const auto& l : p.links) scale += l.mass * p.gravity.norm() * 1.0;
    const double coarse = drift(4e-3), fine = drift(2e-3);
    INFO("n = " << n << ": drift " << coarse << " at dt 4e-3, " << fine << " at 2e-3 (scale "
                << scale << ")");
    CHECK(coarse < 1e-4 * scale);
    // Fourth order: halving dt divides the drift by about 16.
    CHECK(coarse / fine > 10.0);
    CHECK(coarse / fine < 25.0);
  }
}

TEST_CASE("spatial tree: invalid parameters are refused") {
  Random r(5);
  const SpatialTreeParams good = random_tree(r, 3);
  auto refused = [&](auto change) {
    SpatialTreeParams p = good;
    change(p);
    return [p] { SpatialTree("t", p); };
  };
  CHECK_NOTHROW(SpatialTree("t", good));
  CHECK_THROWS_AS(refused([](auto& p) { p.links.clear(); })(), std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[1].joint_name = "j0"; })(), std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[1].joint_name = ""; })(), std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[1].parent = 1; })(), std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[2].axis.setZero(); })(), std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[0].mass = -1.0; })(), std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[0].inertia(0, 0) = -1.0; })(),
                  std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[0].inertia(0, 1) = 1.0; })(),
                  std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.links[0].lower = 1.0, p.links[0].upper = 0.0; })(),
                  std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.angles = core::Vec::Zero(2); })(), std::invalid_argument);
  CHECK_THROWS_AS(refused([](auto& p) { p.gravity.x() = NAN; })(), std::invalid_argument);
  // A revolute leaf carrying a point mass on its own axis moves no inertia.
  CHECK_THROWS_AS(refused([](auto& p) {
                    SpatialLink l;
                    l.joint_name = "spin";
                    l.type = SpatialJointType::revolute;
                    l.inertia.setZero();
                    l.com = l.axis * 0.3;
                    p.links.push_back(l);
                  })(),
                  std::invalid_argument);
  const SpatialTree tree("t", good);
  CHECK(tree.joint_index("j2") == 2);
  CHECK(tree.joint_index("nope") == -1);
  CHECK(tree.joint_name(1) == "j1");
}
