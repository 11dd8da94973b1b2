#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "components/admittance/planar_arm.hpp"
#include "components/admittance/point_mass.hpp"
#include "components/admittance/rigid_body.hpp"
#include "core/integrator.hpp"
#include "core/run_limits.hpp"
#include "scene/components.hpp"
#include "scene/overrides.hpp"
#include "scene/toml_parse_error.hpp"
#include "scene/toml_shape.hpp"
#include "sys/data_dirs.hpp"
#include "sys/read_file.hpp"

namespace stiction::scene {
namespace fs = std::filesystem;

namespace {

// Tables owned by the renderer, the plotter, `verify` and the accuracy verdict (validated
// there, not here).
constexpr const char* kForeignSections[] = {"render", "camera", "overlay", "inset",
                                            "plots",  "verify", "accuracy"};

toml::table parse_text(const std::string& text, const std::string& origin) {
  check_toml_shape(text, origin);  // before toml++: a deep dotted key overflows its stack
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw InputError::at(e.source(), readable_parse_error(e, text));
  }
}

toml::table parse_file(const fs::path& path) {
  std::string text;
  try {
    text = sys::read_regular_file(path);
  } catch (const sys::FileRefused& e) {
    throw InputError(path.string() + ": error: cannot read the scene file: " + e.what());
  }
  return parse_text(text, path.string());
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// Why `name` cannot name a directory under out/, or empty if it can: no separators, not
// "." or "..", no leading dot (hidden, and ".." in disguise), no control characters.
std::string invalid_name_reason(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.size() > 200) return "must be at most 200 characters long";
  if (name.front() == '.') return "must not start with '.'";
  for (const char c : name) {
    if (c == '/' || c == '\\') return "must not contain a path separator ('/' or '\\')";
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return "must not contain control characters";
  }
  return {};
}

core::RunOptions read_simulation(TableReader& root) {
  core::RunOptions run;
  std::optional<TableReader> sim = root.subtable("simulation");
  if (!sim) return run;
  const auto names = core::integrator_names();
  run.integrator = sim->string("integrator", run.integrator);
  if (std::find(names.begin(), names.end(), run.integrator) == names.end()) {
    sim->fail("integrator",
              "unknown integrator '" + run.integrator + "' (expected one of " + join(names) + ")");
  }
  // A tolerance selects the adaptive integrator unless one is named; a fixed-step integrator
  // would silently ignore it, and rk4_adaptive cannot run without one.
  if (sim->has("tolerance")) {
    run.tolerance = sim->positive("tolerance", run.tolerance);
    if (!sim->has("integrator")) {
      run.integrator = core::adaptive_integrator().name;
    } else if (!core::is_adaptive(run.integrator)) {
      sim->fail("tolerance", "only the adaptive integrators (" +
                                 join(core::adaptive_integrator_names()) +
                                 ") use a tolerance (integrator is '" + run.integrator + "')");
    }
  } else if (core::is_adaptive(run.integrator)) {
    sim->fail("integrator", run.integrator +
                                " needs a tolerance: add tolerance = 1e-8 (for example) "
                                "to [simulation]");
  }
  run.dt = sim->positive("dt", run.dt);
  run.duration = sim->positive("duration", run.duration);
  run.output_rate = sim->positive("output_rate", run.output_rate);
  // energy_growth_limit: the key's old name, still read (the same number, now a fraction of
  // the scene's energy scale: core/energy_budget.hpp).
  if (sim->has("energy_growth_limit") && sim->has("energy_tolerance")) {
    sim->fail("energy_growth_limit", "give energy_tolerance or its old name, not both");
  }
  run.energy_tolerance =
      sim->positive(sim->has("energy_growth_limit") ? "energy_growth_limit" : "energy_tolerance",
                    run.energy_tolerance);
  if (const auto violation = core::check_user_run(run))
    sim->fail(violation->key, violation->message);
  if (sim->has("event_resolution")) {
    run.event_resolution = sim->non_negative("event_resolution", run.event_resolution);
  }
  sim->finish();
  return run;
}

}  // namespace

std::vector<fs::path> scene_directories() {
  std::vector<fs::path> dirs;
  for (const fs::path& dir : sys::data_directories()) dirs.push_back(dir / "scenes");
  return dirs;
}

fs::path find_scene(const std::string& name_or_path) {
  std::error_code ec;
  const fs::path as_path(name_or_path);
  if (fs::is_regular_file(as_path, ec)) return as_path;
  const bool looks_like_name = as_path.filename() == as_path && !as_path.has_extension();
  if (looks_like_name) {
    for (const fs::path& dir : scene_directories()) {
      const fs::path candidate = dir / (name_or_path + ".toml");
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
  }
  // Something that is there but is no regular file (a FIFO, a device, a directory that is
  // not a bundled scene's name) is named as what it is by the reader that refuses it
  // (parse_file), not "no such file".
  if (fs::exists(fs::status(as_path, ec))) return as_path;
  std::vector<std::string> names;
  for (const auto& [name, description] : bundled_scenes()) names.push_back(name);
  throw InputError("error: SCENE '" + name_or_path + "': no such file" +
                   (looks_like_name ? " or bundled scene (bundled: " + join(names) + ")" : ""));
}

std::vector<std::pair<std::string, std::string>> bundled_scenes() {
  std::map<std::string, std::string> found;  // the first directory wins, as in find_scene
  for (const fs::path& dir : scene_directories()) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      if (entry.path().extension() != ".toml") continue;
      const std::string name = entry.path().stem().string();
      if (found.contains(name)) continue;
      std::string description;
      try {
        const toml::table doc = toml::parse_file(entry.path().string());
        description = doc["description"].value_or(std::string{});
      } catch (const toml::parse_error&) {
        description = "(unreadable: run `stiction check " + name + "`)";
      }
      found.emplace(name, description);
    }
  }
  return {found.begin(), found.end()};
}

SceneSource SceneSource::from_text(std::string toml_text, std::string origin) {
  SceneSource source;
  source.text = std::move(toml_text);
  source.origin = std::move(origin);
  return source;
}

Scene load_scene(const SceneSource& source, const std::vector<std::string>& overrides) {
  const fs::path path = source.is_text() ? fs::path(source.origin) : find_scene(source.name_or_path);
  toml::table document = source.is_text() ? parse_text(source.text, source.origin) : parse_file(path);
  // The file's own step, before --set: the step guard pilots at it when a run asks for a
  // larger one (a wrong type or value is reported when the scene is built).
  const double file_dt =
      document.at_path("simulation.dt").value<double>().value_or(core::RunOptions{}.dt);
  for (const std::string& assignment : overrides) apply_override(document, assignment);
  Scene scene = build_scene(std::move(document), path, source.externals);
  if (std::isfinite(file_dt) && file_dt > 0.0) {
    scene.authored_dt = std::min(scene.authored_dt, file_dt);
  }
  return scene;
}

void check_expressions(const Scene& scene) {
  for (const auto& expression : scene.expressions)
    expression->check_over(scene.run.duration, scene.run.output_rate);
}

Scene build_scene(toml::table document, const fs::path& path,
                  std::shared_ptr<const ExternalElements> externals) {
  Scene scene;
  scene.path = path;
  scene.externals = std::move(externals);
  scene.document = std::move(document);
  TableReader root(scene.document, "");
  scene.name = root.string("name", path.stem().string());
  // The name becomes the default output directory out/<name>/: one plain path component.
  if (const std::string why = invalid_name_reason(scene.name); !why.empty()) {
    if (root.has("name")) root.fail("name", why);
    throw InputError::at(scene.document.source(), "name: the file name '" + scene.name + "' " +
                                                      why + "; give the scene a `name`");
  }
  scene.description = root.string("description", "");
  for (const char* section : kForeignSections) root.node(section);
  const core::Vec3 gravity = root.vec3("gravity", core::Vec3(0.0, 0.0, -9.8));
  scene.run = read_simulation(root);
  scene.authored_dt = scene.run.dt;

  scene.network = std::make_unique<core::Network>();
  ComponentBuilder builder(*scene.network, gravity, scene.externals.get());
  // A urdf body's `file` is relative to the scene file; a scene given as text (no such
  // file) reads it from the working directory.
  std::error_code ec;
  builder.set_directory(fs::is_regular_file(path, ec) ? path.parent_path() : fs::current_path());
  if (auto bodies = root.subtable("bodies")) {
    for (TableReader& body : builder.entries(*bodies)) builder.add_body(body);
    bodies->finish();
  }
  if (auto impedances = root.subtable("impedances")) {
    for (TableReader& impedance : builder.entries(*impedances)) builder.add_impedance(impedance);
    impedances->finish();
  }
  builder.finish();  // contacts' `settle`
  root.finish();
  if (scene.network->admittances().empty()) {
    throw InputError::at(scene.document.source(), "the scene has no [bodies]");
  }
  scene.run.stick_thresholds = builder.stick_thresholds();  // per contact or joint
  scene.drawing = std::move(builder.drawing());
  // The overlays judge stick and slip with the thresholds the events use.
  const auto threshold_of = [&run = scene.run](const std::string& element) {
    const auto it = run.stick_thresholds.find(element);
    return it != run.stick_thresholds.end() ? it->second : run.default_stick_threshold;
  };
  for (ContactSite& site : scene.drawing.sites.contacts)
    site.stick_threshold = threshold_of(site.name);
  for (JointSite& site : scene.drawing.sites.joints) site.stick_threshold = threshold_of(site.name);
  scene.network->finalize();
  builder.locate_observed();                      // sources reading other elements' signals
  scene.expressions = builder.expressions();
  check_expressions(scene);
  scene.warnings = plausibility_warnings(scene);  // after the build: checks read the network
  return scene;
}

}  // namespace stiction::scene
