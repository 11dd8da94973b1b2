// stiction._run: `stiction run` without its pictures, through the same services
// (services/run_service.hpp): the step guard, the simulation with the GIL released, the
// accuracy estimate and summary.json's content. The rows stay in memory and are handed to
// NumPy without a copy; save() writes trajectory.csv and summary.json as the command does.
#include <atomic>
#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "run_handle.hpp"
#include "io/csv_writer.hpp"
#include "io/summary.hpp"
#include "services/interrupted_run.hpp"
#include "services/output_dir.hpp"
#include "services/run_service.hpp"
#include "services/step_check.hpp"
#include "sys/interrupt.hpp"

namespace stiction::python {

namespace {

std::string refusal_text(const services::PreparedRun& p) {
  const services::StepGuard& g = p.guard;
  char dt[32];
  std::snprintf(dt, sizeof dt, "%g", g.refusal->dt);
  return p.scene.name + ": " + services::step_check_text(g.check) + "; nothing was simulated. " +
         (g.refusal->verified ? "A step that works" : "A smaller step to try") + ": dt=" + dt +
         " (" + g.refusal->how + "); force_step=True runs it anyway";
}

std::shared_ptr<RunHandle> run(const SceneHandle& handle, std::optional<std::string> integrator,
                               std::optional<double> dt, std::optional<double> duration,
                               std::optional<double> tolerance, std::optional<bool> accuracy,
                               bool force_step, bool progress) {
  services::RunRequest request;
  request.overrides = {std::move(integrator), dt, duration, tolerance};
  request.force_step = force_step;
  request.accuracy = accuracy;
  request.progress = progress;
  request.stop = &sys::interrupt_flag();

  auto h = std::make_shared<RunHandle>();
  // The scene as it is now: another thread may set() on it while this one simulates.
  const SceneHandle scene = handle;
  // Ctrl-C stops the run and keeps its rows: only the main thread receives SIGINT.
  std::optional<sys::ScopedInterrupt> interrupt;
  if (on_main_thread()) interrupt.emplace();
  {
    py::gil_scoped_release release;
    h->prepared = std::make_shared<services::PreparedRun>(
        services::prepare_run(scene.fresh(), request));
    services::guard_run(*h->prepared, request);
    if (!h->prepared->guard.refusal) {
      services::RunOutcome outcome = services::simulate_run(*h->prepared, request);
      services::estimate_run_accuracy(*h->prepared, request, outcome);
      h->result = std::move(outcome.result);
      h->summary = std::move(outcome.summary);
      if (outcome.accuracy_interrupted) {
        services::mark_interrupted(h->summary, "accuracy", outcome.time_reached);
      } else if (h->result.interrupted) {
        services::mark_interrupted(h->summary, "simulate", outcome.time_reached);
      }
    }
  }
  interrupt.reset();
  if (h->prepared->guard.refusal) {
    py::object error = error_class("StepRefused")(refusal_text(*h->prepared));
    error.attr("suggested_dt") = h->prepared->guard.refusal->dt;
    error.attr("step_check") = to_python(services::step_check_json(h->prepared->guard.check));
    PyErr_SetObject(error.get_type().ptr(), error.ptr());
    throw py::error_already_set();
  }
  h->status = h->summary.value("status", std::string("ok"));
  return h;
}

// The rows as a (rows, columns) float64 array over the run's own memory.
py::array rows_view(const std::shared_ptr<RunHandle>& h) {
  const core::Trajectory& t = h->result.trajectory;
  const auto rows = static_cast<py::ssize_t>(t.row_count());
  const auto columns = static_cast<py::ssize_t>(t.column_count());
  const double* data = rows > 0 ? t.row(0) : nullptr;
  py::array a(py::dtype::of<double>(), {rows, columns},
              {static_cast<py::ssize_t>(sizeof(double)) * columns,
               static_cast<py::ssize_t>(sizeof(double))},
              data, py::cast(h));
  // Read-only: the arrays are the run's record, shared by every view.
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// Writes what `stiction run --no-video --no-plots` writes into `dir`, under the same rules
// (services/output_dir.hpp: the directory locked, an earlier run's outputs replaced).
// `overwrite`: as --overwrite, write into a non-empty directory that is no stiction output.
std::vector<std::string> save(const RunHandle& h, const std::filesystem::path& dir, bool overwrite) {
  services::OutputDirectory out(dir, services::OutputOptions{overwrite});
  io::write_csv(h.result.trajectory, out / "trajectory.csv");
  out.wrote(out / "trajectory.csv");
  nlohmann::ordered_json summary = h.summary;
  out.wrote(out / "summary.json");
  summary["files"] = out.files();
  io::write_summary(summary, out / "summary.json");
  out.commit();
  return {out.final_path("trajectory.csv").string(), out.final_path("summary.json").string()};
}

}  // namespace

void bind_run(py::module_& m) {
  py::class_<RunHandle, std::shared_ptr<RunHandle>>(m, "_Run")
      .def_property_readonly("columns",
                             [](const RunHandle& h) { return h.result.trajectory.columns(); })
      .def_property_readonly("units",
                             [](const RunHandle& h) {
                               std::vector<std::tuple<std::string, std::string, std::string>> out;
                               for (const core::ColumnInfo& c : h.prepared->infos)
                                 out.emplace_back(c.name, c.unit, c.description);
                               return out;
                             })
      .def_property_readonly("summary", [](const RunHandle& h) { return to_python(h.summary); })
      .def_property_readonly("status", [](const RunHandle& h) { return h.status; })
      .def_property_readonly("steps", [](const RunHandle& h) { return h.result.steps; })
      .def_property_readonly("wall_seconds", [](const RunHandle& h) { return h.result.wall_seconds; })
      .def_property_readonly("instability",
                             [](const RunHandle& h) -> py::object {
                               if (!h.result.instability) return py::none();
                               const core::Instability& i = *h.result.instability;
                               py::dict d;
                               d["time"] = i.time;
                               d["component"] = i.component;
                               d["reason"] = i.reason;
                               return d;
                             })
      .def("rows", &rows_view)
      .def("save", &save, py::arg("dir"), py::arg("overwrite") = false);

  m.def("_run", &run, py::arg("scene"), py::arg("integrator") = py::none(),
        py::arg("dt") = py::none(), py::arg("duration") = py::none(),
        py::arg("tolerance") = py::none(), py::arg("accuracy") = py::none(),
        py::arg("force_step") = false, py::arg("progress") = false);
}

}  // namespace stiction::python
