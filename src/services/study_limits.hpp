// The largest steps `stiction study` reports for each fixed-step integrator, beside what
// `stiction check` predicts: the predicted limits (check's functions on check's bounded
// pilot run), then two bisections over whole runs of the scene, by stability (the run ends
// without instability) and by accuracy (it meets the target). The two share their runs: a
// step is run once, whichever bisection asks first.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"
#include "services/study.hpp"

namespace stiction::services {

// A whole run at one step, measured once.
struct StudyProbe {
  bool stable = false;
  bool meets_target = false;
  std::string failure;  // "unstable", or what breaks the target
  long evaluations = 0;
  double cpu_seconds = 0.0;
  double event_time_error = 0.0;
  double final_value_error = 0.0;
};

// Runs the scene with `integrator` at step h and measures it against the reference.
using ProbeRun = std::function<StudyProbe(const std::string& integrator, double h)>;

class StepLimitSearch {
 public:
  StepLimitSearch(const StudyOptions& options, StudyResult& result, ProbeRun run,
                  StudyLog log)
      : options_(options), result_(result), run_(std::move(run)), log_(std::move(log)) {}

  // result.limits: one per fixed-step integrator of `integrators`, with check's prediction.
  void predict(scene::Scene& scene, const std::vector<std::string>& integrators);
  // Bracket from the grid's rows (largest stable step below the smallest unstable one),
  // widened by doubling or halving from `scene_dt` when the rows have no unstable or no
  // stable step, then bisected in log h down to options.bisection_precision.
  void bisect_stable(StabilityLimit& limit, double scene_dt);
  // Largest step within the target, bracketed by the known runs (rows and probes).
  void bisect_accurate(StabilityLimit& limit);

 private:
  const StudyProbe& probe(const std::string& integrator, double h, int& runs);
  void note(const std::string& text);

  const StudyOptions& options_;
  StudyResult& result_;
  ProbeRun run_;
  StudyLog log_;
  std::map<std::pair<std::string, double>, StudyProbe> probes_;  // by (integrator, h)
};

}  // namespace stiction::services
