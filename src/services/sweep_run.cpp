#include "services/sweep_run.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdint>
#include <exception>
#include <fstream>
#include <iterator>
#include <sstream>
#include <mutex>
#include <thread>

#include "core/simulation.hpp"
#include "io/csv_writer.hpp"
#include "io/summary.hpp"
#include "services/step_guard.hpp"
#include "sys/interrupt.hpp"
#include "text/number_text.hpp"
#include "services/text_hash.hpp"

namespace stiction::services {
namespace fs = std::filesystem;
namespace {

std::string number_text(double v) {
  std::string s;
  io::append_number(s, v);
  return s;
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The plan's `settings` (sweep.hpp): everything but the varied keys that makes a point's run.
// The scene as its document after --set (toml++'s canonical text), so that a scene file with
// --set and the same scene made in Python are one sweep; its source text when that does not
// load without the points' values.
std::vector<std::string> plan_settings(const SweepSettings& settings, const scene::Scene& probe) {
  std::string text;
  try {
    std::ostringstream canonical;
    canonical << toml::toml_formatter(scene::load_scene(settings.scene, settings.overrides).document);
    text = canonical.str();
  } catch (const std::exception&) {
    text = settings.scene.is_text() ? settings.scene.text : file_text(probe.path);
    for (const std::string& o : settings.overrides) text += "\n--set " + o;
  }
  std::vector<std::string> s;
  s.push_back("scene fnv1a64 " + text_hash(text));
  if (settings.run.integrator) s.push_back("--integrator " + *settings.run.integrator);
  if (settings.run.dt) s.push_back("--dt " + number_text(*settings.run.dt));
  if (settings.run.duration) s.push_back("--duration " + number_text(*settings.run.duration));
  if (settings.run.tolerance) s.push_back("--tolerance " + number_text(*settings.run.tolerance));
  return s;
}

std::vector<std::string> point_overrides(const SweepSettings& settings, const SweepPlan& plan,
                                         const SweepPoint& point) {
  std::vector<std::string> overrides = settings.overrides;
  for (std::size_t k = 0; k < plan.keys.size(); ++k) {
    overrides.push_back(plan.keys[k].key + "=" + point.values[k]);
  }
  return overrides;
}

class DiscardRows final : public core::RowSink {
 public:
  void write(const double*, std::size_t, std::size_t) override {}
};

// The work (component-steps, suggest_step.hpp) the trial runs behind one point's suggested
// step may take: a sweep has many points, so a sixth of what `run` allows.
constexpr double kSuggestionBudget = kSuggestionWork / 6.0;

class PointRunner {
 public:
  PointRunner(const SweepSettings& settings, const SweepPlan& plan, const SweepSignals& signals,
              const fs::path& out)
      : settings_(settings),
        plan_(plan),
        signals_(signals),
        out_(out),
        shared_checks_([this](std::size_t i) { return point_scene(plan_.points.at(i)); }) {}

  // The point's table row; empty when a signal stopped it before it had one.
  std::vector<std::string> run(const SweepPoint& point) const {
    std::vector<std::string> row(plan_.columns.size());
    row[0] = std::to_string(point.index);
    for (std::size_t k = 0; k < point.values.size(); ++k) row[1 + k] = point.values[k];
    const std::size_t base = 1 + point.values.size();  // status, steps, wall_s, suggested_dt, note
    try {
      scene::Scene scene = point_scene(point);
      if (scene.network->signal_columns() != signals_.signals) {
        row[base] = "error";
        row[base + 4] = "the values of this point change the scene's signals";
        return row;
      }
      // The step guard, per point (the values may move the limits), its analysis shared
      // among points whose stiffness and mass the values leave alone (step_check.hpp): a
      // point predicted unstable, and failing a trial, is not simulated; its row says so and
      // suggests a step.
      const StepGuard guard =
          guard_step(scene, settings_.force_step, kSuggestionBudget, &shared_checks_, point.index);
      if (guard.refusal) {
        row[base] = "refused";
        row[base + 3] = number_text(guard.refusal->dt);
        row[base + 4] = "not simulated: " + step_check_text(guard.check) + "; try --dt " +
                        number_text(guard.refusal->dt) + " (--force-step runs it anyway)";
        return row;
      }
      // Rows stream to the point's trajectory.csv (--keep all) or nowhere: the table needs
      // only the last row, which the result keeps. A signal stops the point: no row for it.
      scene.run.stop = &sys::interrupt_flag();
      core::RunResult result;
      if (settings_.keep == "all") {
        std::vector<std::string> columns = signals_.signals;
        columns.insert(columns.begin(), "t");
        fs::create_directories(point_dir(point));
        io::CsvStream csv(point_dir(point) / "trajectory.csv", columns);
        result = core::simulate(*scene.network, scene.run, {}, &csv);
        if (!result.interrupted) csv.commit();  // else no complete-looking file
      } else {
        DiscardRows none;
        result = core::simulate(*scene.network, scene.run, {}, &none);
      }
      if (result.interrupted) return {};
      row[base + 1] = std::to_string(result.steps);
      char wall[32];
      std::snprintf(wall, sizeof wall, "%.4g", result.wall_seconds);
      row[base + 2] = wall;
      if (result.instability) {
        const double dt = suggest_step(scene, guard.check, kSuggestionBudget).dt;
        row[base] = "unstable";
        row[base + 3] = number_text(dt);
        row[base + 4] = "instability at t = " +
                        text::significant(result.instability->time, text::kEventTimeDigits) +
                        " s in '" + result.instability->component + "' (" +
                        result.instability->reason + "); try --dt " + number_text(dt);
      } else {
        row[base] = "ok";
        if (guard.warning) row[base + 4] = "step check: " + *guard.warning;
      }
      std::size_t c = base + 5;
      for (const core::SlipHistory& h : result.slip_events) {
        for (const double time :
             {h.monitor.stick_time(), h.monitor.first_slip(), h.monitor.last_stick()}) {
          row[c++] = time >= 0.0 ? number_text(time) : "";
        }
        std::string events;
        for (const core::SlipEvent& e : h.monitor.events()) {
          events += (events.empty() ? "" : ";") + e.kind + ":" + number_text(e.time);
        }
        row[c++] = events;
      }
      const core::Trajectory& tr = result.trajectory;
      for (const std::string& record : signals_.records) {
        const int col = *tr.find(record);
        row[c++] = tr.row_count() > 0 ? number_text(tr.at(tr.row_count() - 1, col)) : "";
      }
      keep(point, scene, result, guard.check);
    } catch (const sys::Interrupted&) {
      return {};  // a signal during the step check or a suggestion's trials: no row
    } catch (const std::exception& e) {
      row[base] = "error";  // scene::InputError and anything else: the point's message
      // Its first line: the table is one line per point (a Python law's error carries a
      // traceback on the lines after).
      const std::string message = e.what();
      row[base + 4] = message.substr(0, message.find('\n'));
    }
    return row;
  }

 private:
  scene::Scene point_scene(const SweepPoint& point) const {
    scene::Scene scene =
        scene::load_scene(settings_.scene, point_overrides(settings_, plan_, point));
    apply_overrides(scene, settings_.run);
    return scene;
  }

  fs::path point_dir(const SweepPoint& point) const {
    char leaf[32];
    std::snprintf(leaf, sizeof leaf, "%06zu", point.index);
    return out_ / "points" / leaf;
  }

  void keep(const SweepPoint& point, const scene::Scene& scene, const core::RunResult& result,
            const StepCheck& check) const {
    if (settings_.keep == "none") return;
    const fs::path dir = point_dir(point);
    fs::create_directories(dir);
    auto summary = io::make_summary(describe_run(scene), result);
    summary["step_check"] = step_check_json(check);
    summary["accuracy"] = {{"method", "off"},
                           {"reason",
                            "a sweep point estimates no accuracy (run the point "
                            "with `stiction run` for its error bars)"}};
    summary["warnings"] = warnings_json(scene.warnings);
    io::write_summary(summary, dir / "summary.json");
  }

  const SweepSettings& settings_;
  const SweepPlan& plan_;
  const SweepSignals& signals_;
  fs::path out_;
  // The points of one dynamics share one step analysis, the first point's of the whole plan
  // (a sweep of mu analyses once, and a shard gives each point the verdict the unsharded
  // sweep gives it).
  mutable SharedStepChecks shared_checks_;
};

}  // namespace

SweepSignals complete_sweep_plan(SweepPlan& plan, const SweepSettings& settings,
                                 const std::vector<std::string>& records,
                                 const std::vector<std::string>& plot) {
  SweepSignals probe;
  {
    scene::Scene scene =
        scene::load_scene(settings.scene, point_overrides(settings, plan, plan.points.front()));
    apply_overrides(scene, settings.run);
    probe.scene_name = scene.name;
    plan.settings = plan_settings(settings, scene);
    probe.signals = scene.network->signal_columns();
    const core::Network& network = *scene.network;
    for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
      if (network.capabilities(i).slip != nullptr) {
        probe.slip_components.push_back(network.impedances()[i]->name());
      }
    }
  }
  probe.records = records.empty() ? probe.signals : records;
  for (const std::string& r : probe.records) {
    if (std::find(probe.signals.begin(), probe.signals.end(), r) == probe.signals.end()) {
      std::string known;
      for (const std::string& s : probe.signals) known += " " + s;
      throw scene::InputError("error: --record " + r + ": not a signal of " + probe.scene_name +
                              "; its signals are:" + known);
    }
  }
  plan.columns = {"point"};
  for (const VaryKey& k : plan.keys) plan.columns.push_back(k.key);
  for (const char* c : {"status", "steps", "wall_s", "suggested_dt", "note"})
    plan.columns.push_back(c);
  for (const std::string& c : probe.slip_components) {
    for (const char* event : {".stick_time", ".first_slip", ".last_stick", ".events"})
      plan.columns.push_back(c + event);
  }
  for (const std::string& r : probe.records) plan.columns.push_back(r);
  plan.plot.clear();
  if (!plot.empty()) {
    for (const std::string& p : plot) {
      if (std::find(plan.columns.begin(), plan.columns.end(), p) == plan.columns.end()) {
        throw scene::InputError("error: --plot " + p + ": not a column of the sweep table");
      }
    }
    plan.plot = plot;
  } else {
    // Every element's first stick and first slip; the report leaves out those no point has
    // and falls back to the first record (plotted_columns).
    for (const std::string& c : probe.slip_components) {
      plan.plot.push_back(c + ".stick_time");
      plan.plot.push_back(c + ".first_slip");
    }
  }
  return probe;
}

std::vector<const SweepPoint*> points_to_run(const SweepPlan& plan, const SweepTable& table,
                                             const Shard& shard) {
  std::vector<const SweepPoint*> todo;
  for (const SweepPoint& p : plan.points) {
    if (shard.owns(p.index) && table.rows.count(p.index) == 0) todo.push_back(&p);
  }
  return todo;
}

unsigned sweep_threads(int jobs, std::size_t todo) {
  const unsigned wanted =
      jobs > 0 ? static_cast<unsigned>(jobs) : std::thread::hardware_concurrency();
  return std::max(
      1u, std::min<unsigned>(wanted, static_cast<unsigned>(std::max<std::size_t>(1, todo))));
}

void run_sweep_points(const SweepSettings& settings, const SweepPlan& plan,
                      const SweepSignals& signals, const fs::path& out,
                      const std::vector<const SweepPoint*>& todo, unsigned jobs, SweepTable& table,
                      const std::function<void(const std::vector<std::string>&)>& append,
                      const std::function<void(std::size_t)>& finished_callback) {
  const PointRunner runner(settings, plan, signals, out);
  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  std::size_t finished = 0;
  std::exception_ptr failure;
  auto work = [&] {
    for (std::size_t i = next++; i < todo.size(); i = next++) {
      if (sys::interrupted()) return;  // SIGINT/SIGTERM: the rows so far stay, resumable
      std::vector<std::string> row = runner.run(*todo[i]);
      if (row.empty()) return;
      std::lock_guard<std::mutex> lock(mutex);
      try {
        if (append) append(row);
      } catch (...) {
        if (!failure) failure = std::current_exception();
        next = todo.size();
        return;
      }
      table.rows[todo[i]->index] = std::move(row);
      ++finished;
      if (finished_callback) finished_callback(finished);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned j = 1; j < jobs; ++j) threads.emplace_back(work);
  work();
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace stiction::services
