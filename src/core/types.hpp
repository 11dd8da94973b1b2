// Vector types shared by every component. The whole system state is one contiguous
// Eigen::VectorXd (the paper's x); components see their slice through these references,
// so no component copies or allocates while the integrator runs.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace stiction::core {

using Vec = Eigen::VectorXd;
using VecRef = Eigen::Ref<Eigen::VectorXd>;
using ConstVecRef = Eigen::Ref<const Eigen::VectorXd>;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

}  // namespace stiction::core
