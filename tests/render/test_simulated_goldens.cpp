// Golden frames of simulated runs (issue 37, "What must be shown"): a wheel spinning out under
// a torque ramp (scenes/wheel_spin_out.toml), a box tipping on a pushed box
// (scenes/box_on_pushed_box.toml) and two spheres colliding (scenes/glancing_spheres.toml),
// each from the side, three-quarter and follow views with badges, force arrows and trails on.
// Unlike the other goldens these come from real runs: the bundled scene is simulated here and
// its frame drawn through frame_renderer_for, the path the video takes, so they show what a
// user's video shows; the events the pictures rest on (the spin-out, the floor letting go,
// the tip) are checked against the closed forms in the scenes' headers first. The scenes are
// short (1 s, 1.1 s and 0.4 s of simulated time; the three cases take about 4 s).
// Regenerate after an intended change (in the renderer or the physics) with
//   STICTION_UPDATE_GOLDEN=1 ./build/tests/render/test_render "[golden]"
// and look at every image (docs/rendering.md, Golden images).
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "core/simulation.hpp"
#include "image/compare.hpp"
#include "image/png.hpp"
#include "render/render_outputs.hpp"
#include "render/render_settings.hpp"
#include "scene/scene.hpp"

using namespace stiction;
using namespace stiction::render;
namespace fs = std::filesystem;

namespace {

const fs::path kSource(STICTION_SOURCE_DIR);

struct SimulatedRun {
  scene::Scene scene;
  core::RunResult result;
  std::vector<double> event_times;
  std::vector<std::string> event_kinds;
};

SimulatedRun simulate_bundled(const std::string& name) {
  SimulatedRun run{
      scene::load_scene(scene::SceneSource((kSource / "scenes" / (name + ".toml")).string())),
      {},
      {},
      {}};
  run.result = core::simulate(*run.scene.network, run.scene.run);
  REQUIRE(run.result.trajectory.row_count() > 10);
  REQUIRE_FALSE(run.result.instability);
  for (const core::SlipHistory& h : run.result.slip_events) {
    for (const core::SlipEvent& e : h.monitor.events()) {
      run.event_times.push_back(e.time);
      run.event_kinds.push_back(e.kind);
    }
  }
  return run;
}

// The scene's own render settings with badges, force arrows and the trail on, at 640x360.
RenderSettings golden_settings(const scene::Scene& s, CameraView view) {
  RenderSettings settings = read_render_settings(s);
  settings.width = 640;
  settings.height = 360;
  settings.camera.view = view;
  settings.overlay.trail = true;
  settings.overlay.layers.badges = true;
  settings.overlay.layers.forces = true;
  return settings;
}

// The first event of `kind` of the element `component`, -1 if none.
double first_event(const SimulatedRun& run, const std::string& component, const std::string& kind) {
  for (const core::SlipHistory& h : run.result.slip_events) {
    if (h.component != component) continue;
    for (const core::SlipEvent& e : h.monitor.events()) {
      if (e.kind == kind) return e.time;
    }
  }
  return -1.0;
}

void check_views(const SimulatedRun& run, const std::string& name, double t) {
  for (const auto& [view, view_name] :
       {std::pair{CameraView::side, "side"}, std::pair{CameraView::three_quarter, "three_quarter"},
        std::pair{CameraView::follow, "follow"}}) {
    INFO(name << ", " << view_name << " at t = " << t);
    const std::unique_ptr<FrameRenderer> renderer =
        frame_renderer_for(run.scene, run.result.trajectory, golden_settings(run.scene, view),
                           run.event_times, run.event_kinds);
    const image::Image frame = renderer->render(t);
    const std::string file = "render_" + name + "_" + view_name + ".png";
    const fs::path dir = fs::path(STICTION_TEST_OUTPUT_DIR) / "simulated_goldens";
    fs::create_directories(dir);
    image::write_png(dir / file, frame);
    const image::CompareResult r =
        image::compare_to_golden(kSource / "tests" / "golden" / file, frame,
                                 fs::path(STICTION_TEST_OUTPUT_DIR) / "failures");
    INFO(r.message);
    CHECK(r.matches);
  }
}

}  // namespace

TEST_CASE("golden: a wheel spinning out under a torque ramp, simulated, three views",
          "[render][golden][simulated]") {
  const SimulatedRun run = simulate_bundled("wheel_spin_out");
  // The picture is of what the header's closed form says: both rim contacts spin out at
  // t* = 3 mu M g R / (2 k) = 0.588 s.
  CHECK(first_event(run, "floor.0", "slip") == Approx(0.588).margin(1e-3));
  CHECK(first_event(run, "floor.3", "slip") == Approx(0.588).margin(1e-3));
  check_views(run, "wheel_spin_out", 0.9);  // 0.31 s after the spin-out: slipping at 0.96 m/s
}

TEST_CASE("golden: a box tipping on a pushed box, simulated, three views",
          "[render][golden][simulated]") {
  const SimulatedRun run = simulate_bundled("box_on_pushed_box");
  // The floor lets go at mu_f (M + m) g / k = 0.1633 s; the upper box's front corners lift at
  // t_tip = (M + m) g (mu_f + w / h) / k = 0.708 s (corners 1 and 3: +x, the front).
  CHECK(first_event(run, "floor.0", "slip") == Approx(0.1633).margin(2e-3));
  CHECK(first_event(run, "upper_on_lower.1", "open") == Approx(0.708).margin(2e-3));
  CHECK(first_event(run, "upper_on_lower.3", "open") == Approx(0.708).margin(2e-3));
  CHECK(first_event(run, "upper_on_lower.0", "open") < 0.0);  // the back edge holds
  check_views(run, "box_on_pushed_box", 1.075);  // leaning back 22 degrees (tipped at 0.708 s)
}

TEST_CASE("golden: two spheres colliding at a glancing angle, simulated, three views",
          "[render][golden][simulated]") {
  const SimulatedRun run = simulate_bundled("glancing_spheres");
  REQUIRE(first_event(run, "touch", "slip") < 0.036);  // touched down before the frame
  check_views(run, "glancing_spheres", 0.036);         // during the 2.6 ms contact
}
