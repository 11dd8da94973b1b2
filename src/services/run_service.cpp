#include "services/run_service.hpp"

#include "services/run_comparison.hpp"
#include "services/verify_settings.hpp"

namespace stiction::services {

PreparedRun prepare_run(scene::Scene scene, const RunRequest& request) {
  PreparedRun p;
  p.scene = std::move(scene);
  apply_overrides(p.scene, request.overrides);
  p.dt_from_overrides = request.overrides.dt.has_value();
  const core::RunOptions& run = p.scene.run;

  // Checked before the simulation: both fail with file:line:col on a bad table or signal.
  p.render_settings = render::read_render_settings(p.scene);
  if (request.check_frames) render::check_frame_count(p.scene, p.render_settings);
  p.columns = p.scene.network->signal_columns();
  p.columns.insert(p.columns.begin(), "t");
  p.infos = core::column_infos(*p.scene.network);
  p.plot_specs = plot::read_plot_specs(p.scene.document, p.scene.path.string(), p.infos);
  if (p.plot_specs.empty()) p.plot_specs = plot::default_plot_specs(p.infos, &p.plots_not_drawn);
  read_verify_settings(p.scene.document, run.duration);  // [verify]: same errors as check/verify
  p.judge_rule = read_judge_rule(p.scene);                // [accuracy]: likewise

  p.warnings = p.scene.warnings;
  return p;
}

void guard_run(PreparedRun& p, const RunRequest& request) {
  // A step predicted unstable is refused before anything is simulated.
  p.guard = guard_step(p.scene, request.force_step);
  if (p.guard.warning) {
    p.warnings.push_back(step_warning(p.scene, p.dt_from_overrides, *p.guard.warning));
  }
}

RunOutcome simulate_run(PreparedRun& p, const RunRequest& request, core::RowSink* sink) {
  RunOutcome o;
  scene::Scene& scene = p.scene;
  scene.run.stop = request.stop;
  o.result = simulate_scene(scene, request.progress, sink);
  const core::RunResult& result = o.result;

  io::RunDescription description = describe_run(scene);
  if (result.instability) {
    o.suggestion = suggested_dt(scene, p.guard.check);
    description.suggested_dt = o.suggestion->dt;
  }
  description.columns = p.infos;
  o.summary = io::make_summary(description, result);
  o.summary["step_check"] = step_check_json(p.guard.check);
  // Plausibility warnings of the scene (scene/plausibility.hpp) and the step guard's ([] if
  // none).
  o.summary["warnings"] = warnings_json(p.warnings);
  o.time_reached = result.trajectory.row_count() > 0
                       ? result.trajectory.at(result.trajectory.row_count() - 1, 0)
                       : 0.0;
  if (result.instability || result.interrupted) {
    o.summary["accuracy"] = {
        {"method", "off"},
        {"reason", result.instability ? "the run was unstable" : "the run was interrupted"}};
  }
  return o;
}

void estimate_run_accuracy(PreparedRun& p, const RunRequest& request, RunOutcome& o) {
  if (o.result.instability || o.result.interrupted) return;
  AccuracySettings settings;
  settings.rule = p.judge_rule;
  if (request.accuracy) settings.mode = *request.accuracy ? AccuracyMode::on : AccuracyMode::off;
  PredictedStepLimits limits;
  if (p.guard.check.applies) {
    limits.chatter_limit = p.guard.check.chatter_limit;
    if (!p.guard.check.unbounded) limits.instability_limit = p.guard.check.instability_limit;
  }
  o.accuracy = estimate_accuracy(p.scene, o.result, limits, settings);
  o.summary["accuracy"] = accuracy_json(o.accuracy);
  o.accuracy_interrupted = o.accuracy.interrupted;
}

}  // namespace stiction::services
