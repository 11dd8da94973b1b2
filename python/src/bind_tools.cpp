// stiction._check, _study, _sweep and _compare: `stiction check --json`, `study`, `sweep` and
// `compare` through the same services (services/check_report.hpp, study.hpp, sweep_run.hpp,
// comparison.hpp), each with the GIL released while it computes (a sweep's points run on
// threads; Python elements take the GIL per call) and Ctrl-C turned into the package's
// Interrupted. python/stiction/_tools.py is the public face.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "bindings.hpp"
#include "services/check_report.hpp"
#include "services/comparison.hpp"
#include "services/study.hpp"
#include "services/sweep_directory.hpp"
#include "services/sweep_run.hpp"
#include "sys/interrupt.hpp"

namespace stiction::python {

namespace {

// Runs `work` with the GIL released and SIGINT caught (on the main thread, the only one that
// receives it); a service that gave up on the signal (sys::Interrupted) becomes
// stiction.Interrupted. Returns whether a signal arrived.
template <class Work>
bool without_gil(const char* what, Work&& work) {
  std::optional<sys::ScopedInterrupt> interrupt;
  if (on_main_thread()) interrupt.emplace();
  bool stopped = false;
  {
    py::gil_scoped_release release;
    try {
      work();
    } catch (const sys::Interrupted&) {
      stopped = true;
    }
    stopped = stopped || sys::interrupted();
  }
  interrupt.reset();
  if (stopped && what != nullptr) {
    py::object error = error_class("Interrupted")(std::string(what) + ": interrupted");
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
  }
  return stopped;
}

// ---- check

py::object check(const SceneHandle& handle) {
  scene::Scene scene = handle.fresh();
  nlohmann::json report;
  without_gil("check", [&] { report = services::check_json(scene, services::check_scene(scene)); });
  return to_python(report);
}

// ---- study

double or_nan(bool has, double v) { return has ? v : std::nan(""); }

py::dict recommendation_dict(const services::Recommendation& r) {
  py::dict d;
  d["integrator"] =
      r.integrator.empty() ? py::object(py::none()) : py::object(py::str(r.integrator));
  d["dt"] = r.dt;
  d["tolerance"] = r.tolerance;
  d["evaluations_per_second"] = r.evaluations_per_second;
  d["cpu_per_second"] = r.cpu_per_second;
  d["event_time_error"] = r.event_time_error;
  d["final_value_error"] = r.final_value_error;
  d["bisected"] = r.bisected;
  d["repeats"] = r.repeats;
  return d;
}

// The table by column, named as study.csv names them, at full precision (NaN where study.csv
// leaves a field empty).
py::dict study_table(const services::StudyResult& r) {
  py::dict table;
  auto column = [&](const std::string& name, auto value_of) {
    py::list values;
    for (const services::StudyRow& row : r.rows) values.append(value_of(row));
    table[py::str(name)] = values;
  };
  using Row = services::StudyRow;
  column("integrator", [](const Row& row) { return row.integrator; });
  column("dt", [](const Row& row) { return row.dt; });
  column("tolerance", [](const Row& row) { return or_nan(row.tolerance > 0.0, row.tolerance); });
  column("status", [](const Row& row) { return row.status; });
  column("unstable_time", [](const Row& row) {
    return or_nan(row.instability.has_value(), row.instability ? row.instability->time : 0.0);
  });
  column("unstable_component", [](const Row& row) {
    return row.instability ? row.instability->component : std::string();
  });
  column("steps", [](const Row& row) { return row.steps; });
  column("evaluations", [](const Row& row) { return row.evaluations; });
  column("wall_seconds", [](const Row& row) { return row.wall_seconds; });
  column("repeats", [](const Row& row) { return row.repeats; });
  column("key_error", [](const Row& row) { return row.key_error; });
  column("worst_signal", [](const Row& row) { return row.worst_signal; });
  for (std::size_t i = 0; i < r.key_signals.size(); ++i) {
    column("error_" + r.key_signals[i], [i](const Row& row) {
      return i < row.signal_errors.size() ? row.signal_errors[i] : std::nan("");
    });
  }
  for (std::size_t i = 0; i < r.event_names.size(); ++i) {
    const std::string& name = r.event_names[i];
    const std::size_t space = name.rfind(' ');
    const std::string element = name.substr(0, space), kind = name.substr(space + 1);
    auto at = [i](const std::vector<double>& v) { return i < v.size() ? v[i] : std::nan(""); };
    column(kind + "_time_" + element, [at](const Row& row) { return at(row.event_times); });
    column(kind + "_error_" + element, [at](const Row& row) { return at(row.event_errors); });
    column(kind + "_relative_error_" + element,
           [at](const Row& row) { return at(row.event_relative_errors); });
  }
  column("cpu_seconds", [](const Row& row) { return row.cpu_seconds; });
  column("event_time_error", [](const Row& row) { return row.event_time_error; });
  column("final_value_error", [](const Row& row) { return row.final_value_error; });
  column("meets_target", [](const Row& row) { return row.meets_target; });
  column("accuracy_failure", [](const Row& row) { return row.accuracy_failure; });
  return table;
}

py::list study_limits(const services::StudyResult& r) {
  py::list limits;
  for (const services::StabilityLimit& l : r.limits) {
    py::dict d;
    d["integrator"] = l.integrator;
    d["predicted"] = l.predicted;
    d["predicted_unbounded"] = l.predicted_unbounded;
    d["predicted_time"] = l.predicted_time;
    d["chatter_free"] = l.chatter_free;
    d["bisected"] = l.bisected;
    d["unstable_above"] = l.unstable_above;
    d["runs"] = l.runs;
    d["note"] = l.note;
    d["accurate"] = l.accurate;
    d["inaccurate_above"] = l.inaccurate_above;
    d["accuracy_failure"] = l.accuracy_failure;
    d["accuracy_runs"] = l.accuracy_runs;
    d["accuracy_note"] = l.accuracy_note;
    limits.append(d);
  }
  return limits;
}

std::shared_ptr<services::StudyResult> study(const SceneHandle& handle,
                                             const std::vector<std::string>& integrators,
                                             const std::vector<double>& dts,
                                             const std::vector<double>& tolerances,
                                             std::optional<double> reference_dt, int repeats,
                                             double target_error, bool progress) {
  services::StudyOptions options;
  options.scene = handle.source;
  options.overrides = handle.overrides;
  options.integrators = integrators;
  options.dts = dts;
  options.tolerances = tolerances;
  options.reference_dt = reference_dt;
  options.repeats = repeats;
  options.target_error = target_error;
  services::StudyLog log;
  if (progress) log = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  auto result = std::make_shared<services::StudyResult>();
  without_gil("study", [&] { *result = services::run_study(options, log); });
  return result;
}

// ---- sweep

struct SweepHandle {
  services::SweepSettings settings;
  services::SweepPlan plan;
  services::SweepSignals signals;
  services::SweepTable table;
  bool interrupted = false;
};

// keys: (key, spec) with spec the command line's LIST ("0.1:1:10", "1,2,4") or (key, values)
// with each value's TOML text.
std::shared_ptr<SweepHandle> sweep(const SceneHandle& handle, const py::list& keys, bool zip,
                                   int jobs, const std::vector<std::string>& records,
                                   const std::vector<std::string>& plot,
                                   std::optional<std::string> integrator, std::optional<double> dt,
                                   std::optional<double> duration, std::optional<double> tolerance,
                                   bool force_step, bool progress) {
  auto h = std::make_shared<SweepHandle>();
  h->settings.scene = handle.source;
  h->settings.overrides = handle.overrides;
  h->settings.run = {std::move(integrator), dt, duration, tolerance};
  h->settings.force_step = force_step;
  h->settings.keep = "none";
  // Named as the command line names it: the scene argument (a text: its scene's name).
  h->plan.scene = handle.source.is_text() ? handle.loaded->name : handle.source.name_or_path;
  h->plan.zip = zip;
  for (const py::handle item : keys) {
    const auto pair = item.cast<py::tuple>();
    const std::string key = pair[0].cast<std::string>();
    if (py::isinstance<py::str>(pair[1])) {
      h->plan.keys.push_back(services::parse_vary(key + "=" + pair[1].cast<std::string>()));
    } else {
      h->plan.keys.push_back({key, pair[1].cast<std::vector<std::string>>()});
      if (h->plan.keys.back().values.empty())
        throw scene::InputError("error: vary " + key + ": no values");
    }
  }
  if (h->plan.keys.empty()) throw scene::InputError("error: sweep: vary at least one key");
  h->plan.points = services::make_points(h->plan.keys, zip);
  {
    py::gil_scoped_release release;  // loads a scene (Python elements take the GIL)
    h->signals = services::complete_sweep_plan(h->plan, h->settings, records, plot);
  }
  h->table.header = h->plan.columns;
  const auto todo = services::points_to_run(h->plan, h->table, services::Shard{});
  const unsigned threads = services::sweep_threads(jobs, todo.size());
  std::function<void(std::size_t)> finished;
  if (progress) {
    finished = [total = todo.size()](std::size_t n) {
      std::fprintf(stderr, "\r  %zu / %zu points%s", n, total, n == total ? "\n" : "");
    };
  }
  h->interrupted = without_gil(nullptr, [&] {
    services::run_sweep_points(h->settings, h->plan, h->signals, {}, todo, threads, h->table, {},
                               finished);
  });
  return h;
}

// ---- compare

std::filesystem::path compare(const py::list& runs, const std::vector<std::string>& signals,
                              const std::filesystem::path& out, const std::string& format) {
  const std::optional<plot::Format> parsed = plot::parse_format(format);
  if (!parsed) throw scene::InputError("error: format: expected png, svg or pdf, not " + format);
  std::vector<core::Trajectory> trajectories;
  trajectories.reserve(runs.size());
  std::vector<services::ComparedRun> compared;
  for (const py::handle item : runs) {
    const auto entry = item.cast<py::tuple>();  // (label, rows, columns, scene handle)
    const auto rows =
        entry[1].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
    core::Trajectory& t = trajectories.emplace_back(entry[2].cast<std::vector<std::string>>());
    if (rows.ndim() != 2 || rows.shape(1) != t.column_count())
      throw std::invalid_argument("compare: rows do not match the columns");
    t.reserve_rows(static_cast<int>(rows.shape(0)));
    for (py::ssize_t r = 0; r < rows.shape(0); ++r) t.append(rows.data(r, 0));
    const auto& scene = entry[3].cast<const SceneHandle&>();
    compared.push_back(
        {entry[0].cast<std::string>(), &t, core::column_infos(*scene.loaded->network)});
  }
  py::gil_scoped_release release;
  return services::write_comparison(compared, signals, out, *parsed);
}

}  // namespace

void bind_tools(py::module_& m) {
  m.def("_check", &check, py::arg("scene"));

  py::class_<services::StudyResult, std::shared_ptr<services::StudyResult>>(m, "_Study")
      .def_property_readonly("scene", [](const services::StudyResult& r) { return r.scene; })
      .def_property_readonly("table", &study_table)
      .def_property_readonly("limits", &study_limits)
      .def_property_readonly(
          "recommendation",
          [](const services::StudyResult& r) { return recommendation_dict(r.recommendation); })
      .def_property_readonly("candidates",
                             [](const services::StudyResult& r) {
                               py::list out;
                               for (const auto& c : r.candidates)
                                 out.append(recommendation_dict(c));
                               return out;
                             })
      .def_property_readonly("orders",
                             [](const services::StudyResult& r) {
                               py::dict out;
                               for (const auto& o : r.orders) out[py::str(o.integrator)] = o.order;
                               return out;
                             })
      .def_property_readonly("reference",
                             [](const services::StudyResult& r) {
                               py::dict d;
                               d["integrator"] = r.reference_integrator;
                               d["dt"] = r.reference_dt;
                               d["steps"] = r.reference_steps;
                               d["wall_seconds"] = r.reference_wall_seconds;
                               d["noise"] = r.reference_noise;
                               d["event_noise"] = r.reference_event_noise;
                               py::dict events;
                               for (std::size_t i = 0; i < r.event_names.size(); ++i)
                                 events[py::str(r.event_names[i])] = r.reference_event_times[i];
                               d["event_times"] = events;
                               return d;
                             })
      .def_property_readonly("key_signals",
                             [](const services::StudyResult& r) { return r.key_signals; })
      .def_property_readonly("notes", [](const services::StudyResult& r) { return r.notes; })
      .def_property_readonly("target_error",
                             [](const services::StudyResult& r) { return r.target_error; })
      .def_property_readonly("total_seconds",
                             [](const services::StudyResult& r) { return r.total_seconds; })
      .def("markdown", [](const services::StudyResult& r) { return services::study_markdown(r); })
      .def("csv", [](const services::StudyResult& r) { return services::study_csv(r); })
      .def(
          "write",
          [](const services::StudyResult& r, const std::filesystem::path& dir) {
            py::gil_scoped_release release;
            services::write_study(r, dir);
          },
          py::arg("dir"));
  m.def("_study", &study, py::arg("scene"), py::arg("integrators"), py::arg("dts"),
        py::arg("tolerances"), py::arg("reference_dt"), py::arg("repeats"), py::arg("target_error"),
        py::arg("progress"));

  py::class_<SweepHandle, std::shared_ptr<SweepHandle>>(m, "_Sweep")
      .def_property_readonly("scene", [](const SweepHandle& h) { return h.plan.scene; })
      .def_property_readonly("scene_name",
                             [](const SweepHandle& h) { return h.signals.scene_name; })
      .def_property_readonly("keys",
                             [](const SweepHandle& h) {
                               std::vector<std::pair<std::string, std::vector<std::string>>> out;
                               for (const auto& k : h.plan.keys) out.emplace_back(k.key, k.values);
                               return out;
                             })
      .def_property_readonly("points",
                             [](const SweepHandle& h) {
                               std::vector<std::vector<std::string>> out;
                               for (const auto& p : h.plan.points) out.push_back(p.values);
                               return out;
                             })
      .def_property_readonly("header", [](const SweepHandle& h) { return h.table.header; })
      .def_property_readonly("rows",
                             [](const SweepHandle& h) {
                               std::vector<std::vector<std::string>> out;
                               for (const auto& [index, row] : h.table.rows) out.push_back(row);
                               return out;
                             })
      .def_property_readonly("plot", [](const SweepHandle& h) { return h.plan.plot; })
      .def_property_readonly("records", [](const SweepHandle& h) { return h.signals.records; })
      .def_property_readonly("interrupted", [](const SweepHandle& h) { return h.interrupted; })
      .def(
          "write",
          [](const SweepHandle& h, const std::filesystem::path& dir, bool overwrite) {
            py::gil_scoped_release release;
            return services::write_sweep(h.plan, h.table, dir, overwrite);
          },
          py::arg("dir"), py::arg("overwrite") = false);
  m.def("_sweep", &sweep, py::arg("scene"), py::arg("keys"), py::arg("zip"), py::arg("jobs"),
        py::arg("records"), py::arg("plot"), py::arg("integrator"), py::arg("dt"),
        py::arg("duration"), py::arg("tolerance"), py::arg("force_step"), py::arg("progress"));

  m.def("_comparison_labels", &services::comparison_labels, py::arg("names"), py::arg("overrides"));
  m.def("_check_comparison_signals", &services::check_comparison_signals, py::arg("labels"),
        py::arg("signal_columns"), py::arg("signals"));
  m.def("_compare", &compare, py::arg("runs"), py::arg("signals"), py::arg("out"),
        py::arg("format"));
}

}  // namespace stiction::python
