#include "core/events.hpp"

#include <cmath>

namespace stiction::core {

void SlipMonitor::observe(double t, const Vec3& slip) {
  const double speed = slip.norm();
  const bool above = speed > threshold_;
  if (seen_ > 0) {
    const bool reversed = sliding_ && above && slip.dot(v1_) < 0.0;
    if (reversed) {
      // Passed through zero within the step: interpolate the zero of the speed, which
      // falls and rises back as |v| does.
      const double t_zero = t1_ + s1_ / (s1_ + speed) * (t - t1_);
      events_.push_back({"stick", t_zero});
      events_.push_back({"slip", t_zero});
    } else if (sliding_ && !above) {
      double t_stick = t1_ + (s1_ - threshold_) / (s1_ - speed) * (t - t1_);
      if (seen_ >= 2 && s2_ > s1_) {
        // The line through the last two sliding steps. Its zero is the stick time if the
        // line itself falls below the threshold within this step, i.e. the slip is
        // decelerating steadily however far below the threshold zero lies; a drop faster
        // than the line (an impact) keeps the threshold crossing.
        const double slope = (s2_ - s1_) / (t1_ - t2_);
        if (s1_ - slope * (t - t1_) <= threshold_) t_stick = t1_ + s1_ / slope;
      }
      events_.push_back({"stick", t_stick});
    } else if (!sliding_ && above) {
      events_.push_back({"slip", t1_ + (threshold_ - s1_) / (speed - s1_) * (t - t1_)});
    }
  }
  sliding_ = above;
  t2_ = t1_;
  s2_ = s1_;
  t1_ = t;
  s1_ = speed;
  v1_ = slip;
  ++seen_;
}

double SlipMonitor::stick_time() const {
  for (const auto& e : events_) {
    if (e.kind == "stick") return e.time;
  }
  return -1.0;
}

}  // namespace stiction::core
