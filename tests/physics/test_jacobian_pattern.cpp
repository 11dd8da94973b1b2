// The implicit step's matrix by compressed differences and the sparse LU (issue 36 item 3,
// core/jacobian_pattern.hpp), on generated towers of boxes (each box on the one below: a
// chain of contacts, one island) and rows of touching spheres on a floor:
// - the pattern's colours: a chain needs about three evaluations per unknown of a body,
//   however tall the tower;
// - the compressed matrix is the one-column-at-a-time matrix to the bit, so the whole run is
//   the same to the bit (a dependency the pattern missed would change the matrix, and the
//   Newton iterates with it);
// - the sparse LU gives the dense LU's solution to Newton's tolerance.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "core/implicit_euler.hpp"
#include "core/islands.hpp"
#include "core/jacobian_pattern.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

std::string box_name(int k) {
  std::ostringstream name;
  name << "box" << k;
  return name.str();
}

// A tower of `count` boxes of 0.3 x 0.3 x 0.1 m on the floor, of random masses and
// friction, turned alternately by a random yaw each way, the top one pushed sideways.
std::string tower(std::mt19937& rng, int count, double dt) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  std::ostringstream text;
  text.precision(17);
  text << "name = \"tower\"\ngravity = [0.0, 0.0, -9.81]\n[simulation]\nintegrator = "
          "\"implicit\"\ndt = "
       << dt << "\nduration = 0.2\n";
  for (int k = 0; k < count; ++k) {
    const double yaw = (k % 2 == 0 ? 1.0 : -1.0) * uniform(0.0, 0.2);
    text << "[bodies." << box_name(k) << "]\ntype = \"rigid_body\"\nmass = " << uniform(0.5, 2.0)
         << "\nshape = \"box\"\nsize = [0.3, 0.3, 0.1]\nposition = [0.0, 0.0, " << 0.05 + 0.1 * k
         << "]\norientation = [" << std::cos(0.5 * yaw) << ", 0.0, 0.0, " << std::sin(0.5 * yaw)
         << "]\n";
    if (k + 1 == count) text << "velocity = [" << uniform(0.1, 0.5) << ", 0.0, 0.0]\n";
    text << "[impedances.c" << k << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << box_name(k)
         << "\"\n";
    if (k > 0) text << "other = \"" << box_name(k - 1) << "\"\n";
    text << "stiffness = 1e6\ndamping = 500.0\nmu = " << uniform(0.3, 0.8) << "\n";
  }
  return text.str();
}

std::string ball_name(int k) {
  std::ostringstream name;
  name << "ball" << k;
  return name.str();
}

// A row of touching spheres on the floor, each pressed into the next, spinning at random.
std::string ball_row(std::mt19937& rng, int count, double dt) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  std::ostringstream text;
  text.precision(17);
  text << "name = \"row\"\ngravity = [0.0, 0.0, -9.81]\n[simulation]\nintegrator = "
          "\"implicit\"\ndt = "
       << dt << "\nduration = 0.5\n";
  const double radius = 0.1;
  for (int k = 0; k < count; ++k) {
    text << "[bodies." << ball_name(k) << "]\ntype = \"rigid_body\"\nmass = " << uniform(0.5, 2.0)
         << "\nshape = \"sphere\"\nradius = " << radius << "\nposition = ["
         << k * (2.0 * radius - 1e-4) << ", 0.0, " << radius << "]\nangular_velocity = ["
         << uniform(-5.0, 5.0) << ", " << uniform(-5.0, 5.0) << ", " << uniform(-5.0, 5.0)
         << "]\n[impedances.floor" << k << "]\ntype = \"kikuuwe_contact\"\nbody = \""
         << ball_name(k) << "\"\nstiffness = 1e6\ndamping = 100.0\nmu = " << uniform(0.2, 0.8)
         << "\n";
    if (k > 0) {
      text << "[impedances.touch" << k << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << ball_name(k)
           << "\"\nother = \"" << ball_name(k - 1)
           << "\"\nstiffness = 1e6\ndamping = 100.0\nmu = " << uniform(0.2, 0.8) << "\n";
    }
  }
  return text.str();
}

struct Run {
  core::Vec x;
  long matrices = 0;
  long evaluations = 0;
  int sparse = 0;
};

Run run(const std::string& text, double dt, double duration, bool compress,
        Eigen::Index sparse_unknowns) {
  auto scene = scene::load_scene(scene::SceneSource::from_text(text, "generated.toml"));
  core::ImplicitEulerStepper stepper(scene.network->state_dim(), dt);
  stepper.set_compressed_differences(compress);
  stepper.set_sparse_unknowns(sparse_unknowns);
  Run out;
  out.x = scene.network->initial_state();
  for (double t = 0.0; t < duration - 1e-12;) {
    t += stepper.advance(*scene.network, t, duration - t, out.x);
    out.sparse = std::max(out.sparse, stepper.sparse_islands());
  }
  out.matrices = stepper.matrices_formed();
  out.evaluations = stepper.matrix_evaluations();
  return out;
}

constexpr Eigen::Index kNever = 1 << 30;

}  // namespace

TEST_CASE(
    "jacobian pattern: a tower is a chain, coloured in three evaluations per unknown of a "
    "box however tall",
    "[implicit][jacobian]") {
  std::mt19937 rng(36);
  for (int count : {2, 5, 12, 30}) {
    auto scene =
        scene::load_scene(scene::SceneSource::from_text(tower(rng, count, 1e-3), "t.toml"));
    const std::vector<bool> solved_flags = core::implicitly_solved_slots(*scene.network);
    const auto islands = core::find_islands(*scene.network);
    REQUIRE(islands.size() == 1);
    std::vector<int> solved;
    for (int e : islands.front().states) {
      if (solved_flags[static_cast<std::size_t>(e)]) solved.push_back(e);
    }
    const core::JacobianPattern pattern =
        core::jacobian_pattern(*scene.network, islands.front(), solved);
    INFO(count << " boxes, " << solved.size() << " unknowns");
    CHECK(solved.size() == static_cast<std::size_t>(13 * count));
    // Box k reaches boxes k - 1, k, k + 1: three colours (two for two boxes).
    CHECK(pattern.groups.size() == static_cast<std::size_t>(13 * std::min(count, 3)));
    // Every column once, in one group; its rows hold its own.
    std::vector<int> seen(solved.size(), 0);
    for (const auto& group : pattern.groups) {
      for (int k : group) ++seen[static_cast<std::size_t>(k)];
    }
    for (std::size_t k = 0; k < solved.size(); ++k) {
      CHECK(seen[k] == 1);
      const auto& rows = pattern.rows[k];
      CHECK(std::binary_search(rows.begin(), rows.end(), static_cast<int>(k)));
      // A box's column reaches at most its neighbours' 13 unknowns each side.
      CHECK(rows.size() <= 39);
    }
  }
}

TEST_CASE(
    "jacobian pattern: compressed differences give the same run to the bit as one column "
    "per evaluation, for a fraction of the evaluations",
    "[implicit][jacobian]") {
  std::mt19937 rng(2036);
  for (int trial = 0; trial < 3; ++trial) {
    for (bool boxes : {true, false}) {
      const int count = boxes ? 4 + trial * 3 : 3 + trial * 2;
      const double dt = trial == 0 ? 1.0 / 240.0 : 1e-3;
      const std::string text = boxes ? tower(rng, count, dt) : ball_row(rng, count, dt);
      INFO((boxes ? "tower of " : "row of ") << count << ", dt " << dt << "\n" << text);
      const Run compressed = run(text, dt, 0.1, true, kNever);
      const Run full = run(text, dt, 0.1, false, kNever);
      REQUIRE(full.x.allFinite());
      REQUIRE(compressed.x.allFinite());
      CHECK(compressed.matrices == full.matrices);
      CHECK((compressed.x - full.x).cwiseAbs().maxCoeff() == 0.0);
      // Three colours of 13 unknowns against 13 per body (the row's contacts may open, which
      // splits it into more islands: then both count the same small ones).
      CHECK(compressed.evaluations <= full.evaluations);
      if (boxes && count > 3) {
        CHECK(static_cast<double>(compressed.evaluations) <=
              3.0 / count * static_cast<double>(full.evaluations) + 1e-9);
      }
    }
  }
}

TEST_CASE(
    "jacobian pattern: the sparse LU steps a tower as the dense LU does, to Newton's "
    "tolerance",
    "[implicit][jacobian]") {
  std::mt19937 rng(7);
  // 16 and 24 boxes: 208 and 312 unknowns, 18% and 12% of the matrix in the pattern.
  for (int count : {16, 24}) {
    const std::string text = tower(rng, count, 1e-3);
    INFO(count << " boxes\n" << text);
    // 20 steps: the pushed top box slides and its corners switch between sticking and
    // slipping, where rounding differences grow; over 0.2 s they reach 2e-6 relative.
    const Run sparse = run(text, 1e-3, 0.02, true, 1);
    const Run dense = run(text, 1e-3, 0.02, true, kNever);
    REQUIRE(dense.x.allFinite());
    REQUIRE(sparse.x.allFinite());
    CHECK(sparse.sparse == 1);
    CHECK(dense.sparse == 0);
    const double scale = dense.x.cwiseAbs().maxCoeff();
    CHECK((sparse.x - dense.x).cwiseAbs().maxCoeff() <= 1e-10 * scale);
  }
}
