// Dense output of a variable step: the cubic Hermite interpolant of the state over a step of
// length h from both ends' values and derivatives, x0 and f0 at its start, x1 and f1 at its
// end. Exact for motions cubic in time (free flight), error h^4 / 384 |x''''| otherwise,
// which is of the order of a fourth-order method's own error over the step.
#pragma once

#include "core/types.hpp"

namespace stiction::core {

// The interpolant at t0 + s h, s in [0, 1], into `out`.
inline void hermite_state(const Vec& x0, const Vec& f0, const Vec& x1, const Vec& f1, double h,
                          double s, Vec& out) {
  const double s2 = s * s, s3 = s2 * s;
  const double w_x0 = 2.0 * s3 - 3.0 * s2 + 1.0, w_x1 = 1.0 - w_x0;
  const double w_f0 = h * (s3 - 2.0 * s2 + s), w_f1 = h * (s3 - s2);
  out.noalias() = w_x0 * x0 + w_x1 * x1 + w_f0 * f0 + w_f1 * f1;
}

}  // namespace stiction::core
