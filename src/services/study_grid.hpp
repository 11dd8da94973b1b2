// The default step grid of `stiction study` for one fixed-step integrator: from well inside
// to past the instability limit that `stiction check` predicts (core::predict_step_limit),
// so that the table shows where the answer stops being accurate and where the run blows up.
#pragma once

#include <string>
#include <vector>

#include "core/stability.hpp"

namespace stiction::services {

struct StepGrid {
  std::vector<double> steps;  // coarse to fine
  // The steps above the predicted instability limit (expected to go unstable); 0 when the
  // grid does not pass it (no bounded prediction, or the limit is beyond `longest`).
  int past_limit = 0;
  std::string note;  // why the grid is not the cliff grid, or what it left out; may be empty
};

// With a bounded prediction L (max_step) and chatter-free step C <= L:
//   past the limit:          1.6 L, 1.25 L
//   just inside it:          0.95 L
//   between C and L:         geometric points, ratio at most 1.5
//   just inside chatter:     0.95 C (when C < L)
//   well inside:             scene_dt x 2^k below 0.95 C / 1.1, down to `finest`
// Steps above `longest` are left out (a run needs a few steps). Without a bounded
// prediction (unbounded, or unstable at every step): the scene's dt x 8, 4, 2, 1, 1/2, ...
// down to `finest`, as before the limits were known.
StepGrid default_step_grid(double scene_dt, const core::StepLimit& predicted, double finest,
                           double longest);

}  // namespace stiction::services
