// The spatial tree's per-link working arrays (world-frame spatial quantities, see
// spatial_algebra.hpp), sized once in the constructor so that no evaluation allocates.
// kinematics() fills the poses, joint axes and link inertias at q; the algorithms
// (spatial_tree_aba.cpp, spatial_tree.cpp) use the rest.
#pragma once

#include <vector>

#include "components/admittance/spatial_algebra.hpp"
#include "components/admittance/spatial_tree.hpp"

namespace stiction::components {

struct SpatialTree::Scratch {
  explicit Scratch(int n)
      : R(n), p(n), com(n), S(n), I(n), v(n), c(n), a(n), pA(n), IA(n), U(n), D(n), u(n) {}
  std::vector<core::Mat3> R;               // link frame orientation, link to world
  std::vector<core::Vec3> p;               // link frame origin (world)
  std::vector<core::Vec3> com;             // centre of mass (world)
  std::vector<spatial::Vec6> S;            // joint motion subspace (world, at the origin)
  std::vector<spatial::Mat6> I;            // link spatial inertia (world, at the origin)
  std::vector<spatial::Vec6> v, c, a, pA;  // velocity, velocity-product accel., accel., bias force
  std::vector<spatial::Mat6> IA;           // articulated (or composite) inertia
  std::vector<spatial::Vec6> U;            // IA S
  std::vector<double> D, u;                // S^T IA S, tau - S^T pA

  // Fills R, p, com, S and I at joint positions q (spatial_tree.cpp).
  void kinematics(const SpatialTreeParams& params, core::ConstVecRef q);
};

}  // namespace stiction::components
