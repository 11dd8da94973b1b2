// PoseTrack: poses and signals at any time, interpolated from the trajectory's rows.
#include <algorithm>
#include <cmath>
#include <limits>

#include "render/scene_view.hpp"

namespace stiction::render {

PoseTrack::PoseTrack(const core::Trajectory& trajectory, const Drawing& scene)
    : trajectory_(trajectory) {
  const auto t_col = trajectory.find("t");
  if (!t_col || trajectory.row_count() == 0) {
    throw RenderError("the trajectory has no rows (nothing to render)");
  }
  t_ = trajectory.column(*t_col);
  auto need = [&](const std::string& name) {
    const auto c = trajectory.find(name);
    if (!c) throw RenderError("the renderer needs the signal '" + name + "', absent from the run");
    return *c;
  };
  for (const auto& b : scene.bodies) {
    Columns c;
    if (b.kind == BodyVisual::Kind::tree) {
      for (const auto& link : b.tree->params().links) {
        c.theta.push_back(need(b.name + ".theta." + link.joint_name));
      }
    } else if (b.kind == BodyVisual::Kind::arm) {
      for (std::size_t i = 0; i < b.lengths.size(); ++i) {
        c.theta.push_back(need(b.name + ".theta." + std::to_string(i)));
      }
    } else {
      for (const char* axis : {"x", "y", "z"}) c.p.push_back(need(b.name + ".p." + axis));
      if (b.kind != BodyVisual::Kind::block) {
        for (const char* axis : {"w", "x", "y", "z"}) c.q.push_back(need(b.name + ".q." + axis));
      }
    }
    columns_.push_back(std::move(c));
  }
}

int PoseTrack::column(const std::string& name) const {
  const auto c = trajectory_.find(name);
  return c ? *c : -1;
}

double PoseTrack::column_peak(int column) const {
  // Asked for every frame (a source's arrow is scaled by its peak): a pass over the rows
  // each time made a run's cost grow with frames x rows.
  const auto known = peaks_.find(column);
  if (known != peaks_.end()) return known->second;
  double peak = 0.0;
  for (int r = 0; r < trajectory_.row_count(); ++r) {
    peak = std::max(peak, std::abs(trajectory_.at(r, column)));
  }
  peaks_.emplace(column, peak);
  return peak;
}

std::pair<int, double> PoseTrack::locate(double t) const {
  if (t <= t_.front() || t_.size() == 1) return {0, 0.0};
  if (t >= t_.back()) return {static_cast<int>(t_.size()) - 2, 1.0};
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  const int r = static_cast<int>(it - t_.begin()) - 1;
  const double span = t_[r + 1] - t_[r];
  return {r, span > 0.0 ? (t - t_[r]) / span : 0.0};
}

double PoseTrack::value(int column, double t) const {
  const auto [r, w] = locate(t);
  if (t_.size() == 1) return trajectory_.at(0, column);
  return (1.0 - w) * trajectory_.at(r, column) + w * trajectory_.at(r + 1, column);
}

core::Vec3 PoseTrack::position(int body, double t) const {
  const auto& p = columns_[body].p;
  return {value(p[0], t), value(p[1], t), value(p[2], t)};
}

core::Quat PoseTrack::orientation(int body, double t) const {
  const auto& q = columns_[body].q;
  if (q.empty()) return core::Quat::Identity();
  const auto [r, w] = locate(t);
  auto at = [&](int row) {
    return core::Quat(trajectory_.at(row, q[0]), trajectory_.at(row, q[1]),
                      trajectory_.at(row, q[2]), trajectory_.at(row, q[3]));
  };
  if (t_.size() == 1) return at(0).normalized();
  core::Quat a = at(r), b = at(r + 1);
  if (a.dot(b) < 0.0) b.coeffs() = -b.coeffs();
  core::Quat m;
  m.coeffs() = (1.0 - w) * a.coeffs() + w * b.coeffs();
  return m.normalized();
}

double PoseTrack::angle(int body, int joint, double t) const {
  return value(columns_[body].theta[static_cast<std::size_t>(joint)], t);
}

double PoseTrack::signal(const std::string& name, double t) const {
  if (const auto c = trajectory_.find(name)) return value(*c, t);
  double sum = 0.0;
  bool any = false;
  for (int c = 0; c < trajectory_.column_count(); ++c) {
    const std::string& column = trajectory_.columns()[c];
    if (is_axis_of(column, name)) {
      const double v = value(c, t);
      sum += v * v;
      any = true;
    }
  }
  return any ? std::sqrt(sum) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace stiction::render
