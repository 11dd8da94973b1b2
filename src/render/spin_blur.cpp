#include "render/spin_blur.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::render {

SpinDuringFrame spin_during_frame(const PoseTrack& poses, int body, double t, double exposure) {
  SpinDuringFrame out;
  if (!(exposure > 0.0)) return out;
  // Angular velocity in the body frame from two orientations 1 ms apart (or less), so that
  // even 1000 rad/s turns only 1 rad between them.
  const double delta = std::min(exposure, 1e-3);
  const double t0 = std::max(poses.start_time(), t - 0.5 * delta);
  const double t1 = std::min(poses.end_time(), t0 + delta);
  if (!(t1 > t0)) return out;
  const core::Quat q0 = poses.orientation(body, t0), q1 = poses.orientation(body, t1);
  core::Quat d = q0.conjugate() * q1;  // body-frame rotation from t0 to t1
  if (d.w() < 0.0) d.coeffs() = -d.coeffs();
  const double s = d.vec().norm();
  if (s < 1e-12) return out;
  const double angle = 2.0 * std::atan2(s, d.w());
  const core::Vec3 axis = d.vec() / s;
  out.axis = to_glm(axis);
  out.angle = static_cast<float>(angle / (t1 - t0) * exposure);
  return out;
}

float blur_angle(float turned) {
  // Below kSharp per frame the pattern moves smoothly and stays sharp (slow spins look as
  // they always did); from there the blur grows to the full rotation at half a turn per
  // frame, where the pattern repeats and would otherwise alias.
  constexpr float kSharp = 0.3f, kHalfTurn = 3.14159265f;
  if (turned <= kSharp) return 0.0f;
  return std::min(turned, (turned - kSharp) * kHalfTurn / (kHalfTurn - kSharp));
}

void apply_spin_blur(std::vector<DrawItem>& items, const PoseTrack& poses, double t,
                     double exposure) {
  for (DrawItem& item : items) {
    if (item.material.kind != MaterialKind::sphere_pattern || item.body < 0) continue;
    const SpinDuringFrame spin = spin_during_frame(poses, item.body, t, exposure);
    item.material.spin_axis = spin.axis;
    item.material.spin_blur = blur_angle(spin.angle);
  }
}

}  // namespace stiction::render
