// The spatial tree's setup, kinematics, signals, energy, and its two reference algorithms:
// the joint-space inertia by composite rigid bodies and the bias force by recursive
// Newton-Euler. Every spatial quantity lives in the world frame at the origin
// (spatial_algebra.hpp), so the joint axis of link i is simply
//   revolute:  S_i = (a_i, p_i x a_i)   (the unit axis a_i through the joint origin p_i),
//   prismatic: S_i = (0, a_i),
// and link velocities add along the tree: v_i = v_parent + S_i qd_i. With that,
//   H_ij = S_i^T Ic_i S_j for j an ancestor of i (or i itself), Ic_i the composite inertia
//   of the subtree from link i; H_ij = 0 when neither is an ancestor of the other;
//   c_i = S_i^T sum_{k in subtree(i)} (I_k a_k + v_k x* I_k v_k), where a_k is link k's
//   acceleration at zero joint acceleration with the base accelerating at -g.
// Both are O(n^2) at worst (a chain), O(n) per row; for tests and the energy check, while
// derivative() uses the O(n) articulated-body algorithm (spatial_tree_aba.cpp).
#include "components/admittance/spatial_tree.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "components/admittance/spatial_tree_scratch.hpp"

namespace stiction::components {
namespace {

bool finite(const core::Vec3& v) { return v.allFinite(); }

// Symmetric and positive semi-definite, to rounding.
bool valid_inertia(const core::Mat3& I) {
  if (!I.allFinite()) return false;
  const double scale = I.cwiseAbs().maxCoeff();
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) return false;
  const Eigen::SelfAdjointEigenSolver<core::Mat3> eig(0.5 * (I + I.transpose()),
                                                      Eigen::EigenvaluesOnly);
  return eig.eigenvalues().minCoeff() >= -1e-12 * scale;
}

}  // namespace

void SpatialTree::Scratch::kinematics(const SpatialTreeParams& params, core::ConstVecRef q) {
  const int n = static_cast<int>(params.links.size());
  const core::Mat3 R_base = params.base_orientation.toRotationMatrix();
  for (int i = 0; i < n; ++i) {
    const SpatialLink& l = params.links[i];
    const core::Mat3& Rp = l.parent < 0 ? R_base : R[l.parent];
    const core::Vec3& pp = l.parent < 0 ? params.base_position : p[l.parent];
    const core::Mat3 Rj = Rp * l.rotation.toRotationMatrix();  // joint frame
    const core::Vec3 pj = pp + Rp * l.origin;
    const core::Vec3 axis = Rj * l.axis;
    if (l.type == SpatialJointType::revolute) {
      R[i] = Rj * Eigen::AngleAxisd(q[i], l.axis).toRotationMatrix();
      p[i] = pj;
      S[i] << axis, pj.cross(axis);
    } else {
      R[i] = Rj;
      p[i] = pj + axis * q[i];
      S[i] << core::Vec3::Zero(), axis;
    }
    com[i] = p[i] + R[i] * l.com;
    I[i] = spatial::inertia_at_origin(l.mass, com[i], R[i] * l.inertia * R[i].transpose());
  }
}

SpatialTree::SpatialTree(std::string name, const SpatialTreeParams& params)
    : core::JointSpace(std::move(name)), params_(params) {
  const int n = joint_count();
  const std::string who = "spatial_tree '" + this->name() + "'";
  if (n < 1) throw std::invalid_argument(who + ": no joints");
  if (!params_.gravity.allFinite() || !finite(params_.base_position) ||
      !(params_.base_orientation.norm() > 1e-12) ||
      !params_.base_orientation.coeffs().allFinite()) {
    throw std::invalid_argument(who + ": gravity, base position and orientation must be finite");
  }
  params_.base_orientation.normalize();
  std::unordered_set<std::string> names;
  for (int i = 0; i < n; ++i) {
    SpatialLink& l = params_.links[i];
    const std::string joint = who + ": joint " + std::to_string(i) +
                              (l.joint_name.empty() ? "" : " ('" + l.joint_name + "')");
    if (l.joint_name.empty()) throw std::invalid_argument(joint + " needs a name");
    if (!names.insert(l.joint_name).second) {
      throw std::invalid_argument(joint + ": the name is used by another joint");
    }
    if (l.parent < -1 || l.parent >= i) {
      throw std::invalid_argument(joint + ": parent must be -1 (the base) or an earlier joint");
    }
    if (!(l.axis.norm() > 1e-12) || !finite(l.axis)) {
      throw std::invalid_argument(joint + ": the axis must be finite and non-zero");
    }
    l.axis.normalize();
    if (!finite(l.origin) || !l.rotation.coeffs().allFinite() || !(l.rotation.norm() > 1e-12)) {
      throw std::invalid_argument(joint + ": origin and rotation must be finite");
    }
    l.rotation.normalize();
    if (!(l.mass >= 0.0) || !std::isfinite(l.mass) || !finite(l.com)) {
      throw std::invalid_argument(joint + ": the link needs a finite mass >= 0 and com");
    }
    if (!valid_inertia(l.inertia)) {
      throw std::invalid_argument(joint +
                                  ": the link inertia must be symmetric positive semi-definite");
    }
    if (std::isnan(l.lower) || std::isnan(l.upper) || l.lower > l.upper) {
      throw std::invalid_argument(joint + ": needs lower <= upper");
    }
  }
  if (params_.angles.size() != 0 && params_.angles.size() != n) {
    throw std::invalid_argument(who + ": angles must have " + std::to_string(n) + " entries");
  }
  if (params_.rates.size() != 0 && params_.rates.size() != n) {
    throw std::invalid_argument(who + ": rates must have " + std::to_string(n) + " entries");
  }
  scratch_ = std::make_shared<Scratch>(n);
  // Every joint must move some inertia, or its acceleration is undefined (D_i = 0 in the
  // articulated-body algorithm): e.g. a revolute joint carrying only point masses on its axis.
  core::Vec x0(2 * n);
  initial_state(x0);
  core::Vec qdd(n);
  forward_dynamics(x0.head(n), core::Vec::Zero(n), core::Vec::Zero(n), qdd);
  for (int i = 0; i < n; ++i) {
    const double D = scratch_->D[i];
    if (!(D > 1e-12 * scratch_->IA[i].norm()) || !std::isfinite(D)) {
      throw std::invalid_argument(who + ": joint '" + params_.links[i].joint_name +
                                  "' moves no inertia (massless links?)");
    }
  }
}

int SpatialTree::joint_index(const std::string& name) const {
  for (int i = 0; i < joint_count(); ++i) {
    if (params_.links[i].joint_name == name) return i;
  }
  return -1;
}

std::vector<std::string> SpatialTree::state_labels() const {
  std::vector<std::string> labels;
  for (const auto& l : params_.links) labels.push_back("theta." + l.joint_name);
  for (const auto& l : params_.links) labels.push_back("omega." + l.joint_name);
  return labels;
}

void SpatialTree::initial_state(core::VecRef x) const {
  const int n = joint_count();
  x.setZero();
  if (params_.angles.size() == n) x.head(n) = params_.angles;
  if (params_.rates.size() == n) x.tail(n) = params_.rates;
}

void SpatialTree::derivative(core::ConstVecRef x, core::ConstVecRef u_hat,
                             core::VecRef x_dot) const {
  const int n = joint_count();
  forward_dynamics(x.head(n), x.tail(n), u_hat, x_dot.tail(n));
  x_dot.head(n) = x.tail(n);
}

std::vector<core::SignalInfo> SpatialTree::signals() const {
  std::vector<std::string> axes;
  bool all_revolute = true;
  for (const auto& l : params_.links) {
    axes.push_back(l.joint_name);
    all_revolute = all_revolute && l.type == SpatialJointType::revolute;
  }
  // One signal holds every joint, so a tree with prismatic joints mixes units.
  return {{.name = "theta",
           .axes = axes,
           .unit = all_revolute ? "rad" : "rad or m",
           .frame = "joint",
           .description = "joint angle (revolute) or travel (prismatic)"},
          {.name = "omega",
           .axes = axes,
           .unit = all_revolute ? "rad/s" : "rad/s or m/s",
           .frame = "joint",
           .description = "joint rate"}};
}

void SpatialTree::write_signals(core::ConstVecRef x, core::VecRef out) const { out = x; }

std::vector<LinkPose> SpatialTree::link_poses(core::ConstVecRef q) const {
  Scratch& s = *scratch_;
  s.kinematics(params_, q);
  std::vector<LinkPose> poses(params_.links.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    poses[i].p = s.p[i];
    poses[i].q = core::Quat(s.R[i]).normalized();
  }
  return poses;
}

double SpatialTree::energy(core::ConstVecRef x) const {
  const int n = joint_count();
  Scratch& s = *scratch_;
  s.kinematics(params_, x.head(n));
  double kinetic = 0.0, potential = 0.0;
  for (int i = 0; i < n; ++i) {
    const int parent = params_.links[i].parent;
    s.v[i] = (parent < 0 ? spatial::Vec6::Zero() : s.v[parent]) + s.S[i] * x[n + i];
    kinetic += 0.5 * s.v[i].dot(s.I[i] * s.v[i]);
    potential -= params_.links[i].mass * params_.gravity.dot(s.com[i]);
  }
  return kinetic + potential;
}

void SpatialTree::mass_matrix(core::ConstVecRef q, Eigen::Ref<Eigen::MatrixXd> H) const {
  const int n = joint_count();
  Scratch& s = *scratch_;
  s.kinematics(params_, q);
  for (int i = 0; i < n; ++i) s.IA[i] = s.I[i];
  for (int i = n - 1; i >= 0; --i) {
    const int parent = params_.links[i].parent;
    if (parent >= 0) s.IA[parent] += s.IA[i];
  }
  H.setZero();
  for (int i = 0; i < n; ++i) {
    const spatial::Vec6 F = s.IA[i] * s.S[i];
    H(i, i) = s.S[i].dot(F);
    for (int j = params_.links[i].parent; j >= 0; j = params_.links[j].parent) {
      H(i, j) = H(j, i) = s.S[j].dot(F);
    }
  }
}

void SpatialTree::bias(core::ConstVecRef q, core::ConstVecRef qd, core::VecRef c) const {
  const int n = joint_count();
  Scratch& s = *scratch_;
  s.kinematics(params_, q);
  spatial::Vec6 a_base;
  a_base << core::Vec3::Zero(), -params_.gravity;  // gravity as an upward base acceleration
  for (int i = 0; i < n; ++i) {
    const int parent = params_.links[i].parent;
    s.v[i] = (parent < 0 ? spatial::Vec6::Zero() : s.v[parent]) + s.S[i] * qd[i];
    s.a[i] = (parent < 0 ? a_base : s.a[parent]) + spatial::motion_cross(s.v[i], s.S[i]) * qd[i];
    s.pA[i] = s.I[i] * s.a[i] + spatial::force_cross(s.v[i], s.I[i] * s.v[i]);
  }
  for (int i = n - 1; i >= 0; --i) {
    c[i] = s.S[i].dot(s.pA[i]);
    const int parent = params_.links[i].parent;
    if (parent >= 0) s.pA[parent] += s.pA[i];
  }
}

}  // namespace stiction::components
