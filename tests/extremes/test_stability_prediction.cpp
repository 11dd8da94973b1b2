// The predicted stable step (core/stability) against what runs of the scene do: the
// prediction must not hang on which states happen to be sampled, and it must bracket the
// real limit, which the energy monitor finds in whole runs.
#include <catch2/catch.hpp>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>
#include <string>

#include "core/stability.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

core::StepLimit predict(const std::string& scene_name, const std::string& integrator,
                        int per_regime) {
  auto scene = scene::load_scene(scene_name);
  const auto states = core::sample_states(*scene.network, scene.run, per_regime);
  return core::predict_step_limit(*scene.network, integrator, states);
}

bool runs_clean(const std::string& scene_name, const std::string& integrator, double dt) {
  auto scene = scene::load_scene(scene_name, {"simulation.integrator=\"" + integrator + "\""});
  core::RunOptions options = scene.run;
  options.dt = dt;
  return !core::simulate(*scene.network, options).instability;
}

}  // namespace

TEST_CASE("sphere_roll rk4: the same prediction from 3, 10 or 30 states per regime",
          "[stability]") {
  const double reference = predict("sphere_roll", "rk4", 10).max_step;
  for (int per_regime : {3, 30}) {
    const auto limit = predict("sphere_roll", "rk4", per_regime);
    INFO(per_regime << " states per regime: " << limit.max_step << " s");
    CHECK(limit.max_step == Approx(reference).epsilon(1e-3));
  }
}

TEST_CASE("sphere_roll: a run at 0.5x of the predicted rk4 and symplectic_euler limits is clean, "
          "at 1.1x it is caught", "[stability]") {
  // Not 0.9x: the energy monitor now sees gains of 1% of the energy scale (issue 26), and
  // sphere_roll gains that much below its linear limit (a mode growing < 5% per step is left
  // out of the prediction): symplectic Euler from 0.6x in the 2 mm fall onto the plane
  // (+1.1%), rk4 at 0.9x in the roll (+4.7%).
  for (const std::string integrator : {"rk4", "symplectic_euler"}) {
    const auto limit = predict("sphere_roll", integrator, 10);
    REQUIRE_FALSE(limit.unbounded);
    REQUIRE(limit.max_step > 0.0);
    const bool below = runs_clean("sphere_roll", integrator, 0.5 * limit.max_step);
    const bool above = runs_clean("sphere_roll", integrator, 1.1 * limit.max_step);
    std::printf("sphere_roll %s: predicted %.4g s (chatter-free below %.4g s); 0.5x %s, 1.1x %s\n",
                integrator.c_str(), limit.max_step, limit.chatter_free_step,
                below ? "clean" : "unstable", above ? "clean" : "unstable");
    CHECK(below);
    CHECK_FALSE(above);
  }
}

TEST_CASE("sphere_roll rk4: stuck contact friction chatters below the runaway limit, bounded, "
          "so the energy monitor does not stop the run", "[stability]") {
  const auto limit = predict("sphere_roll", "rk4", 10);
  // The stuck tangential spring (K = 1e7 N/m against 2/7 M) oscillates from ~2.1e-4 s under
  // RK4, but its force is clamped at mu N, so it never grows the energy: runs between the
  // two limits end without an instability (check and study report the chatter instead:
  // it does spoil the slip events, e.g. the stick time at 4e-4 s).
  CHECK(limit.chatter_free_step < 0.6 * limit.max_step);
  CHECK(runs_clean("sphere_roll", "rk4", 0.5 * (limit.chatter_free_step + limit.max_step)));
}

TEST_CASE("two_link_lugre at 1e-4 s: the unstable bristle state is caught by its bound, though "
          "the energy does not grow", "[stability]") {
  auto scene = scene::load_scene("two_link_lugre");
  core::RunOptions options = scene.run;
  options.dt = 1e-4;
  const auto r = core::simulate(*scene.network, options);
  REQUIRE(r.instability);
  std::printf("two_link_lugre at 1e-4 s: stopped at t = %.4g s in %s (%s)\n", r.instability->time,
              r.instability->component.c_str(), r.instability->reason.c_str());
  CHECK(r.instability->component.find("friction") != std::string::npos);
  CHECK(r.instability->reason.find("bound") != std::string::npos);
  // The prediction from the scene's own (converged) run puts the limit below 1e-4 s.
  CHECK(predict("two_link_lugre", "rk4", 10).max_step < 1e-4);
}

namespace {

struct Drop {
  double damping = 20.0;   // of every contact, N s/m
  double height = 0.0;     // of every sphere above its floor at t = 0; 0: resting (settled)
  double duration = 0.05;  // s
};

// A scene of spheres, each on its own floor contact (stiffness, mass and radius per sphere);
// `only` >= 0 keeps that sphere alone.
std::string resting_spheres(const std::vector<std::array<double, 3>>& spheres, int only,
                            const Drop& drop = {}) {
  // energy_tolerance: the energy monitor's budget is the whole scene's (one scale, one rise),
  // so whether a stuck friction's chatter counts would couple the spheres; these tests are
  // about the step map's groups, so chatter never counts here.
  std::string text = "name = \"resting\"\n[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = " +
                     std::to_string(drop.duration) + "\nenergy_tolerance = 1e6\n";
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    if (only >= 0 && static_cast<std::size_t>(only) != i) continue;
    const auto [stiffness, mass, radius] = spheres[i];
    const std::string b = "ball_number_" + std::to_string(i);
    text += "[bodies." + b + "]\ntype = \"rigid_body\"\nshape = \"sphere\"\nmass = " +
            std::to_string(mass) + "\nradius = " + std::to_string(radius) + "\nposition = [" +
            std::to_string(2.0 * static_cast<double>(i)) + ", 0.0, " +
            std::to_string(radius + drop.height) +
            "]\n[impedances.floor_under_" + b + "]\ntype = \"kikuuwe_contact\"\nbody = \"" + b +
            "\"\nstiffness = " + std::to_string(stiffness) + "\ndamping = " +
            std::to_string(drop.damping) + "\nmu = 0.4\nsettle = " +
            (drop.height > 0.0 ? "false" : "true") + "\n";
  }
  const auto path = std::filesystem::temp_directory_path() /
                    ("stiction_resting_" + std::to_string(::getpid()) + "_" +
                     std::to_string(only + 1) + ".toml");
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace

TEST_CASE("separate bodies: the predicted limit of the whole scene is the smallest of each "
          "body's alone", "[stability]") {
  // The analysis splits the step map into the groups of states that nothing couples (here
  // one per sphere) and solves each alone: the answer must not change.
  const std::vector<std::array<double, 3>> spheres{
      {3.1e6, 0.7, 0.05}, {1.3e7, 2.3, 0.11}, {6.0e5, 0.4, 0.08}};
  for (const std::string integrator : {"rk4", "symplectic_euler"}) {
    double smallest = INFINITY;
    for (int i = 0; i < 3; ++i) {
      const std::string file = resting_spheres(spheres, i);
      smallest = std::min(smallest, predict(file, integrator, 3).max_step);
      std::filesystem::remove(file);
    }
    const std::string file = resting_spheres(spheres, -1);
    const double whole = predict(file, integrator, 3).max_step;
    std::filesystem::remove(file);
    std::printf("%s: whole scene %.6g s, smallest alone %.6g s\n", integrator.c_str(), whole, smallest);
    CHECK(whole > 0.0);
    CHECK(whole == Approx(smallest).epsilon(2e-3));
  }
}

TEST_CASE("sampled states are bounded whatever the number of regimes, each regime first",
          "[stability]") {
  // Spheres dropped from 0.2 m onto undamped floors of different stiffness: their contacts
  // open and close at unrelated times, so the run passes through many combined regimes.
  std::vector<std::array<double, 3>> spheres;
  for (int i = 0; i < 8; ++i) spheres.push_back({2e5 * (1 + i), 0.3 + 0.2 * i, 0.05 + 0.01 * i});
  const std::string file = resting_spheres(spheres, -1, {0.0, 0.2, 2.0});
  auto scene = scene::load_scene(file);
  std::filesystem::remove(file);
  const auto states = core::sample_states(*scene.network, scene.run, 10);
  CHECK(states.size() == core::kMaxSampledStates);
  CHECK(states.front().t == 0.0);  // the first regime's first state
  for (std::size_t i = 1; i < states.size(); ++i) CHECK(states[i - 1].t <= states[i].t);
  // A scene with few regimes keeps all its states.
  auto few_regimes = scene::load_scene("sphere_roll");
  const auto few = core::sample_states(*few_regimes.network, few_regimes.run, 10);
  CHECK(few.size() < core::kMaxSampledStates);
}
