// Stick/slip events of a contact or joint, detected at every integration step from its
// slip velocity: "stick" when the slip stops (its speed falls below the threshold after
// sliding, or its direction reverses between two steps, i.e. it passed through zero, as in
// a bounce), "slip" when the speed rises above the threshold again (a bouncing body that
// lands again, a joint pushed past its limit).
// A stick time is the zero crossing of the straight line through the last two sliding
// steps: while a contact slides, friction is saturated and the slip speed falls linearly,
// so this removes the bias of the threshold (about threshold / slope), whatever the step.
// Where the line does not reach the threshold within the step of the detection (the speed
// dropped faster: an impact), the threshold crossing is used.
#pragma once

#include <string>
#include <vector>

#include "core/types.hpp"

namespace stiction::core {

struct SlipEvent {
  std::string kind;  // "stick" or "slip"
  double time = 0.0;
};

class SlipMonitor {
 public:
  explicit SlipMonitor(double threshold) : threshold_(threshold) {}
  void observe(double t, const Vec3& slip);
  double threshold() const { return threshold_; }
  const std::vector<SlipEvent>& events() const { return events_; }
  // First stick event, or a negative value if the pair never stuck after sliding.
  double stick_time() const;

 private:
  double threshold_;
  bool sliding_ = false;
  int seen_ = 0;
  Vec3 v1_ = Vec3::Zero();  // slip at the previous step
  double t1_ = 0, s1_ = 0;  // previous step: time, speed
  double t2_ = 0, s2_ = 0;  // the step before it
  std::vector<SlipEvent> events_;
};

}  // namespace stiction::core
