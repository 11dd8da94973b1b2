#include "services/study_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stiction::services {
namespace {

std::string format_g(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

// Powers of two times the scene's step, from the largest not above `top` down to `finest`:
// the scene's own step stays on the grid, so its row answers "is my step accurate".
std::vector<double> ladder(double scene_dt, double top, double finest) {
  std::vector<double> steps;
  if (!(top >= finest)) return steps;
  int k = static_cast<int>(std::floor(std::log2(top / scene_dt)));
  // log2 rounding: step down until the first rung is really not above `top`.
  while (scene_dt * std::ldexp(1.0, k) > top * (1.0 + 1e-12)) --k;
  for (;; --k) {
    const double dt = scene_dt * std::ldexp(1.0, k);
    if (dt < finest * (1.0 - 1e-9)) break;
    steps.push_back(dt);
  }
  return steps;
}

}  // namespace

StepGrid default_step_grid(double scene_dt, const core::StepLimit& predicted, double finest,
                           double longest) {
  StepGrid grid;
  const double limit = predicted.max_step;
  if (predicted.skipped || predicted.unbounded || !(limit > 0.0)) {
    grid.steps = ladder(scene_dt, 8.0 * scene_dt, finest);
    grid.note = predicted.skipped
                    ? "no prediction (too many states for the step analysis): the grid is the "
                      "scene's dt x 8, 4, 2, ..."
                : predicted.unbounded
                    ? "predicted stable at every step up to " + format_g(limit) +
                          " s: the grid is the scene's dt x 8, 4, 2, ... and does not pass a limit"
                    : "no stable step predicted: the grid is the scene's dt x 8, 4, 2, ...";
    return grid;
  }
  const double chatter =
      predicted.chatter_free_step > 0.0 ? std::min(predicted.chatter_free_step, limit) : limit;

  std::vector<double> cliff{1.6 * limit, 1.25 * limit, 0.95 * limit};
  grid.past_limit = 2;
  const double span = limit / chatter;
  if (span > 1.0 + 1e-9) {
    const int intervals = static_cast<int>(std::ceil(std::log(span) / std::log(1.5)));
    for (int j = intervals - 1; j >= 1; --j) {
      cliff.push_back(chatter * std::pow(span, static_cast<double>(j) / intervals));
    }
    cliff.push_back(0.95 * chatter);
  }
  // 0.95 L and the top interior point can nearly coincide: keep the larger one.
  std::sort(cliff.rbegin(), cliff.rend());
  std::vector<double> steps;
  for (double dt : cliff) {
    if (!steps.empty() && steps.back() / dt < 1.05) continue;
    steps.push_back(dt);
  }
  const double inside = 0.95 * chatter / 1.1;
  for (double dt : ladder(scene_dt, inside, finest)) steps.push_back(dt);

  const auto too_long =
      std::remove_if(steps.begin(), steps.end(), [&](double dt) { return dt > longest; });
  if (too_long != steps.end()) {
    const int dropped = static_cast<int>(steps.end() - too_long);
    grid.past_limit = std::max(0, grid.past_limit - dropped);
    grid.note = std::to_string(dropped) + " step(s) above " + format_g(longest) +
                " s (a quarter of the duration) left out" +
                (grid.past_limit == 0
                     ? ": the grid does not pass the predicted limit " + format_g(limit) + " s"
                     : std::string());
    steps.erase(too_long, steps.end());
  }
  grid.steps = std::move(steps);
  return grid;
}

}  // namespace stiction::services
