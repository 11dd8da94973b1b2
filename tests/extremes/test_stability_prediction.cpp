// The predicted stable step (core/stability) against what runs of the scene do: the
// prediction must not hang on which states happen to be sampled, and it must bracket the
// real limit, which the energy monitor finds in whole runs.
#include <catch2/catch.hpp>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <unistd.h>
#include <vector>
#include <string>

#include "core/spectrum.hpp"
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

TEST_CASE("spectrum: a stuck contact's step map on which Eigen's real Schur fails has radius 1",
          "[stability]") {
  // The implicit step map of a ball of 1000 rolling ones (spheres_1000: mass 0.3, radius 0.2,
  // K = 1e7) at t = 0.85 s, h = 0.0063 s, states p.x v.x q.w q.y w.y e.0: Eigen 3.4's
  // EigenSolver does not converge on it, and its eigenvalues read as a radius of 4630 made
  // the guard call the scene's stuck friction chattering above 0.006 s.
  Eigen::MatrixXd phi(6, 6);
  phi << 1, 0.0045003885788053605, 0, 0, 0.00035992228353427558, -0.28560727165236216,  //
      -0.0, 0.71434739386001911, -0.0, -0.0, 0.05713052122781518, -45.334487589179197,  //
      0, -0.0096402422542659523, 0.99942011253301977, -0.024073869601892527,
      -0.00077180222008762947, -1.5299543341769968,  //
      0, -0.0057879383600005574, 0.02407386959761278, 0.99942011253301977,
      -0.00046338500196942719, -0.91857456962905215,  //
      0, 3.5706575767473474, 0, 0, 0.28586848465211717, 566.68109486450942,  //
      0, 1.360034626915906e-06, 0, 0, -2.720069253824218e-07, 0.00037454921880254418;
  const Eigen::EigenSolver<Eigen::MatrixXd> plain(phi, false);
  INFO("Eigen's EigenSolver: info " << static_cast<int>(plain.info()));
  const auto radius = core::spectral_radius(phi);
  REQUIRE(radius.has_value());
  CHECK(*radius == Approx(1.0).epsilon(1e-9));
  // Its eigenvalues, checked against the matrix: det(phi - mu I) = 0 for each.
  const auto mu = core::eigenvalues(phi);
  REQUIRE(mu.has_value());
  for (const std::complex<double>& m : *mu) {
    const Eigen::MatrixXcd shifted =
        phi.cast<std::complex<double>>() - m * Eigen::MatrixXcd::Identity(6, 6);
    CHECK(shifted.jacobiSvd().singularValues().minCoeff() < 1e-9);
  }
  CHECK_FALSE(core::spectral_radius(Eigen::MatrixXd::Constant(2, 2, NAN)).value() < INFINITY);
}

TEST_CASE("implicit: generated rolling balls are stable and chatter-free at every step up to "
          "1 s, as their runs at 0.1 s show", "[stability]") {
  // A rolling ball's linearization grows at a few 1/s about its orbit (its orientation
  // turns the body-frame spin), and backward Euler amplifies a growing mode by 1/(1 - h
  // lambda), more than the flow's exp(h lambda): measured against the flow, a ball at 10
  // rad/s was predicted to chatter above 0.08 s. The runs keep the roll exact.
  std::mt19937 rng(20261206);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); };
  std::ostringstream text;
  text.precision(17);
  text << "name = \"rolling_balls\"\ngravity = [0.0, 0.0, -9.81]\n[simulation]\n"
       << "integrator = \"implicit\"\ndt = 0.1\nduration = 4.0\noutput_rate = 10.0\n";
  struct Ball { double mass, radius, mu, v0, factor; };
  std::vector<Ball> balls;
  for (int k = 0; k < 6; ++k) {
    const Ball b{uniform(0.1, 3.0), uniform(0.05, 0.4), uniform(0.1, 0.6), uniform(1.0, 4.0),
                 uniform(0.0, 1.0) < 0.5 ? 0.4 : 2.0 / 3.0};
    balls.push_back(b);
    // An odd orientation: a random unit quaternion.
    Eigen::Vector4d q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    q.normalize();
    const double inertia = b.factor * b.mass * b.radius * b.radius;
    const std::string name = std::string("ball_") + static_cast<char>('a' + k);
    text << "[bodies." << name << "]\ntype = \"rigid_body\"\nmass = " << b.mass
         << "\nshape = \"sphere\"\nradius = " << b.radius << "\ninertia = [" << inertia << ", "
         << inertia << ", " << inertia << "]\nposition = [0.0, " << 2.0 * k << ", " << b.radius
         << "]\nvelocity = [" << b.v0 << ", 0.0, 0.0]\norientation = [" << q[0] << ", " << q[1]
         << ", " << q[2] << ", " << q[3] << "]\n[impedances.floor_" << name
         << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << name
         << "\"\nstiffness = 1e7\ndamping = " << 10.0 * b.mass / 0.3 << "\nmu = " << b.mu
         << "\nsettle = true\n";
  }
  auto scene = scene::load_scene(scene::SceneSource::from_text(text.str(), "rolling_balls.toml"));
  const auto states = core::sample_states(*scene.network, scene.run, 10);
  const auto limit = core::predict_step_limit(*scene.network, "implicit", states, 1e-4, 1.0);
  INFO(text.str());
  CHECK(limit.unbounded);
  CHECK(limit.chatter_free_step == 1.0);

  const auto run = core::simulate(*scene.network, scene.run);
  REQUIRE_FALSE(run.instability);
  const auto& tr = run.trajectory;
  const int last = tr.row_count() - 1;
  for (int k = 0; k < 6; ++k) {
    const Ball& b = balls[static_cast<std::size_t>(k)];
    const double rolling = b.v0 / (1.0 + b.factor);  // v = v0 / (1 + J / (m r^2))
    const double stick = b.v0 * b.factor / ((1.0 + b.factor) * b.mu * 9.81);  // 2 v0/(7 mu g) solid
    if (stick > 3.5) continue;  // still sliding at the end
    const std::string name = std::string("ball_") + static_cast<char>('a' + k);
    INFO(name << ": stick at " << stick << " s, rolling at " << rolling << " m/s");
    CHECK(tr.at(last, *tr.find(name + ".v.x")) == Approx(rolling).epsilon(1e-7));
    // Stuck from the stick on: one stick, no slip after it.
    bool found = false;
    for (const auto& h : run.slip_events) {
      if (h.component != "floor_" + name) continue;
      found = true;
      CHECK(h.monitor.count("stick") == 1);
      CHECK(h.monitor.count("slip") == 0);
      CHECK(h.monitor.stick_time() == Approx(stick).epsilon(1e-6));
    }
    CHECK(found);
  }
}
