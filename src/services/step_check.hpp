// The step guard (issue 26): before anything is simulated, the predicted limits of the run's
// integrator on its scene (the analysis `stiction check` does: the step map linearized at
// states sampled from a pilot run, core/stability.hpp) and the verdict on the run's step:
//   ok        below both limits;
//   chatter   above the step where stuck friction chatters (bounded by its limit force, but
//             sticks come late or not at all) and below the instability limit: a warning;
//   unstable  above the instability limit: the command exits 3 before simulating, unless
//             --force-step.
// The prediction is a guard, not a proof: the run's own monitors stay on.
//
// The pilot runs at the smaller of the run's step and the step the scene file sets (a
// larger step asked on the command line must not hide the regimes it would blow up in), and
// its cost is bounded (app/pilot.hpp). Results are cached by the scene's content and the
// settings (step_check_cache.hpp), so a repeated run pays nothing.
#pragma once

#include <cstddef>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/stability.hpp"
#include "scene/scene.hpp"
#include "services/dynamics_fingerprint.hpp"

namespace stiction::services {

struct StepCheck {
  std::string integrator;
  double dt = 0.0;
  bool applies = true;     // false for rk4_adaptive (no fixed step to check)
  // The network has more states than the dense analysis handles (core::kMaxAnalysedStates):
  // not checked, and `reason` says so.
  bool skipped = false;
  int states = 0;  // the network's state dimension
  int island_states = 0;  // states in its largest island (core/islands.hpp)
  bool unbounded = false;  // no instability found up to kMaxAnalysedStep
  // Largest stable step found; 0: unstable at every step analysed (from lowest_step up).
  double instability_limit = 0.0;
  // The step above which stuck friction chatters (<= instability_limit); equal to it when
  // nothing chatters below the instability.
  double chatter_limit = 0.0;
  double limiting_time = 0.0;  // time of the pilot state that limits the step
  double lowest_step = 0.0;    // the analysis starts here: a limit of 0 means "below this"
  double pilot_dt = 0.0;
  double pilot_duration = 0.0;  // of the scene's duration, the part the pilot covered
  bool pilot_shortened = false;
  double analysis_seconds = 0.0;  // wall time of the analysis (0 when cached)
  bool cached = false;
  // Taken from another scene of the same dynamics (a sweep's point: SharedStepChecks).
  bool shared = false;
  bool forced = false;  // --force-step: run even though the verdict is `unstable`
  // Above a predicted limit (instability or chatter), a trial of the step itself (bounded
  // as a pilot run, against half the step) ran stable and accurate: the verdict is `ok`.
  bool trial_confirmed = false;
  std::string trial;  // what the trial found, when one ran

  // "ok", "chatter", "unstable" or "not_checked" (see the top of this file).
  std::string verdict() const;
  // Why the verdict is "not_checked".
  std::string reason() const;
  // The step the advice starts from: 0.8 times the smaller limit (below the chatter limit).
  double safe_step() const;
};

inline constexpr double kMaxAnalysedStep = 1.0;  // s
// States linearized per regime of the pilot (at most core::kMaxSampledStates in all): a
// scene with one regime (LuGre and Dahl arms have no switching law) gets its 48 states
// spread over the whole pilot, not 10, or a fast phase between two of them goes unseen
// (two_link_dahl over 1.5 s: rk4's limit 9.3e-4 s with 10 states, 1.05e-4 s with 48).
inline constexpr int kStatesPerRegime = 48;

// The check of scene.run (integrator, dt) on the scene; the pilot runs at no more than
// scene.authored_dt (the scene file's own step). Throws sys::Interrupted when a signal
// arrives during the analysis.
StepCheck check_step(scene::Scene& scene);

// The step checks of a sweep's points (from any thread), shared among points of the same
// linear dynamics: a point whose DynamicsFingerprint matches an earlier point's takes the
// limits of the analysis of the first point of the whole sweep (the lowest index) with that
// fingerprint, judged at its own step (`shared`). The limits also depend on the regimes a
// pilot visits, which a friction coefficient can change, so which point is analysed is a
// property of the plan, never of the order in which threads or shards meet the points: a
// point's verdict is the same unsharded, sharded, on any number of threads and after a
// resubmission (a Slurm array's merged table equals the unsharded one). The guard confirms
// by a trial before it refuses or warns, and every run keeps its own monitors.
class SharedStepChecks {
 public:
  // `load(i)`: the scene of the sweep's point i as the point runs it (values and overrides
  // applied); it may throw (that point has no fingerprint and represents nothing).
  explicit SharedStepChecks(std::function<scene::Scene(std::size_t)> load);
  // The check of `scene`, the scene of point `point`.
  StepCheck check(scene::Scene& scene, std::size_t point);

 private:
  // The lowest point index whose fingerprint matches `fingerprint`, at most `point`.
  std::size_t representative(const DynamicsFingerprint& fingerprint, std::size_t point);

  std::function<scene::Scene(std::size_t)> load_;
  mutable std::mutex mutex_;
  // Fingerprints of points 0 .. scanned_-1, as the distinct ones with the first point that has
  // each (points that did not load are skipped).
  std::size_t scanned_ = 0;
  std::vector<std::pair<DynamicsFingerprint, std::size_t>> firsts_;
  // Each representative's analysis, computed once by the first thread that needs it.
  std::map<std::size_t, std::shared_future<StepCheck>> analyses_;
};

// The limits of a prediction (core::predict_step_limit from lowest_step up) as a check of
// `dt` with `integrator`.
StepCheck step_check_from(const core::StepLimit& limit, const std::string& integrator, double dt,
                          double lowest_step);

// summary.json's `step_check` (DESIGN section 4).
nlohmann::ordered_json step_check_json(const StepCheck& check);

// One line for stderr, e.g. "dt = 0.0037 s is above rk4's predicted instability limit
// 0.00238 s on this scene (limiting state at t = 0 s)".
std::string step_check_text(const StepCheck& check);

}  // namespace stiction::services
