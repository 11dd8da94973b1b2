// Simulation I written as one loop, the paper's algorithm (27) with fixed-size Eigen types
// and no network: the baseline that prices the modular architecture (issue 5). It must
// produce the same trajectory as the network; bench_step checks that before timing.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>

namespace stiction::bench {

struct FusedSphere {
  // Parameters of Simulation I (DESIGN section 1).
  double M = 0.3, R = 0.2, K = 1e7, B = 10.0, mu = 0.1, g = 9.8;
  double J = 0.4 * 0.3 * 0.2 * 0.2;
  // State: x = [p, v, q, w] (13) and the contact's friction state e (2).
  Eigen::Matrix<double, 13, 1> x;
  Eigen::Vector2d e = Eigen::Vector2d::Zero();

  FusedSphere() {
    x.setZero();
    x.segment<3>(0) = Eigen::Vector3d(0, 0, 1.01 * R);
    x.segment<3>(3) = Eigen::Vector3d(2, 0, 0);
    x[6] = 1.0;
  }

  // (27d)-(27e): contact impedance and rigid-body admittance at one stage.
  void stage(const Eigen::Matrix<double, 13, 1>& s, const Eigen::Vector2d& es, double tau,
             Eigen::Matrix<double, 13, 1>& xi, Eigen::Vector2d& eps) const {
    const Eigen::Vector3d p = s.segment<3>(0), v = s.segment<3>(3), w = s.segment<3>(10);
    const Eigen::Quaterniond q = Eigen::Quaterniond(s[6], s[7], s[8], s[9]).normalized();
    const Eigen::Vector3d a(0, 0, -R);
    const Eigen::Vector3d vc = v + (q * w).cross(a);
    const double depth = R - p.z();
    const double N = depth > 0.0 ? std::max(0.0, K * depth - B * vc.z()) : 0.0;
    const double BtK = B + tau * K;
    Eigen::Vector2d f = BtK * vc.head<2>() + K * es;
    const double norm = f.norm(), limit = mu * N;
    if (norm <= limit) {
      eps = vc.head<2>();
    } else {
      f *= norm > 0.0 ? limit / norm : 0.0;
      eps = (f - K * es) / BtK;
    }
    const Eigen::Vector3d fF(-f.x(), -f.y(), N);
    const Eigen::Vector3d torque_body = q.conjugate() * a.cross(fF);
    xi.segment<3>(0) = v;
    xi.segment<3>(3) = fF / M + Eigen::Vector3d(0, 0, -g);
    xi[6] = -0.5 * s.segment<3>(7).dot(w);
    xi.segment<3>(7) = 0.5 * (s[6] * w + Eigen::Vector3d(s.segment<3>(7)).cross(w));
    xi.segment<3>(10) = torque_body / J;  // w x Jw = 0 for a sphere
  }

  void step_rk4(double T) {
    static constexpr double offset[4] = {0.0, 0.5, 0.5, 1.0};
    static constexpr double tau[4] = {0.5, 0.5, 1.0, 1.0};
    static constexpr double weight[4] = {1.0 / 6, 2.0 / 6, 2.0 / 6, 1.0 / 6};
    Eigen::Matrix<double, 13, 1> xi[4];
    Eigen::Vector2d eps[4];
    for (int r = 0; r < 4; ++r) {
      const Eigen::Matrix<double, 13, 1> s = r == 0 ? x : Eigen::Matrix<double, 13, 1>(x + (offset[r] * T) * xi[r - 1]);  // (27c)
      const Eigen::Vector2d es = r == 0 ? e : Eigen::Vector2d(e + (offset[r] * T) * eps[r - 1]);  // (27b)
      stage(s, es, tau[r] * T, xi[r], eps[r]);
    }
    for (int r = 0; r < 4; ++r) {
      x += (T * weight[r]) * xi[r];  // (27h)
      e += (T * weight[r]) * eps[r];  // (27g)
    }
    x.segment<4>(6).normalize();
  }
};

}  // namespace stiction::bench
