// The implicit step's matrix by compressed differences and the sparse LU (issue 36 item 3,
// core/jacobian_pattern.hpp), on generated towers of boxes (each box on the one below: a
// chain of contacts, one island) and rows of touching spheres on a floor:
// - the pattern's colours: a chain needs about three evaluations per unknown of a body,
//   however tall the tower;
// - the compressed matrix is the one-column-at-a-time matrix to the bit, so the whole run is
//   the same to the bit (a dependency the pattern missed would change the matrix, and the
//   Newton iterates with it);
// - the sparse LU gives the dense LU's solution to Newton's tolerance;
// - on generated piles with a contact between every two bodies (one large island), columns
//   evaluated on their stars step as the whole island's columns do, to Newton's tolerance,
//   for a fraction of the evaluations.
#include <Eigen/Geometry>
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
  long evaluations = 0;        // matrix evaluations, each of an island or a star
  long whole_evaluations = 0;  // every evaluation, in whole-network units
  int sparse = 0;
};

// A pile of `count` spheres and boxes of random sizes, masses, orientations and spins on a
// jittered grid 0.3 m apart over the floor (3 x 3 a layer), thrown at one another, with a
// contact declared between every two (touching or not) and each on the floor.
std::string pile(std::mt19937& rng, int count, double dt) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  std::ostringstream text;
  text.precision(17);
  text << "name = \"pile\"\ngravity = [0.0, 0.0, -9.81]\n[simulation]\nintegrator = "
          "\"implicit\"\ndt = "
       << dt << "\nduration = 0.2\n";
  for (int k = 0; k < count; ++k) {
    Eigen::Quaterniond q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    q.normalize();
    text << "[bodies." << box_name(k) << "]\ntype = \"rigid_body\"\nmass = " << uniform(0.2, 2.0);
    if (k % 2 == 0) {
      text << "\nshape = \"sphere\"\nradius = " << uniform(0.05, 0.12);
    } else {
      text << "\nshape = \"box\"\nsize = [" << uniform(0.05, 0.15) << ", " << uniform(0.05, 0.15)
           << ", " << uniform(0.05, 0.15) << "]";
    }
    const Eigen::Vector3d at(0.3 * (k % 3 - 1), 0.3 * (k / 3 % 3 - 1), 0.15 + 0.3 * (k / 9));
    const Eigen::Vector3d jitter(uniform(-0.03, 0.03), uniform(-0.03, 0.03), uniform(0.0, 0.03));
    const Eigen::Vector3d p = at + jitter;
    const Eigen::Vector3d v =
        -2.0 * Eigen::Vector3d(at.x(), at.y(), 0.0) +
        Eigen::Vector3d(uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-0.5, 0.5));
    text << "\nposition = [" << p.x() << ", " << p.y() << ", " << p.z() << "]\norientation = ["
         << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]\nvelocity = [" << v.x()
         << ", " << v.y() << ", " << v.z() << "]\nangular_velocity = [" << uniform(-5, 5) << ", "
         << uniform(-5, 5) << ", " << uniform(-5, 5) << "]\n[impedances.floor" << k
         << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << box_name(k)
         << "\"\nstiffness = 1e5\ndamping = 100.0\nmu = " << uniform(0.2, 0.8) << "\n";
    for (int other = 0; other < k; ++other) {
      text << "[impedances.pair" << other << "_" << k << "]\ntype = \"kikuuwe_contact\"\nbody = \""
           << box_name(k) << "\"\nother = \"" << box_name(other)
           << "\"\nstiffness = 1e5\ndamping = 100.0\nmu = " << uniform(0.2, 0.8) << "\n";
    }
  }
  return text.str();
}

Run run(const std::string& text, double dt, double duration, bool compress,
        Eigen::Index sparse_unknowns, bool stars = true, bool detach = true) {
  auto scene = scene::load_scene(scene::SceneSource::from_text(text, "generated.toml"));
  core::ImplicitEulerStepper stepper(scene.network->state_dim(), dt);
  stepper.set_compressed_differences(compress);
  stepper.set_sparse_unknowns(sparse_unknowns);
  stepper.set_star_columns(stars);
  stepper.set_detach_contacts(detach);
  Run out;
  out.x = scene.network->initial_state();
  for (double t = 0.0; t < duration - 1e-12;) {
    t += stepper.advance(*scene.network, t, duration - t, out.x);
    out.sparse = std::max(out.sparse, stepper.sparse_islands());
  }
  out.matrices = stepper.matrices_formed();
  out.evaluations = stepper.matrix_evaluations();
  out.whole_evaluations = stepper.evaluations();
  return out;
}

// A generated scene of one island (structural: as `check` sees it), its solved entries and
// its pattern.
struct OneIsland {
  explicit OneIsland(const std::string& text)
      : scene(scene::load_scene(scene::SceneSource::from_text(text, "generated.toml"))) {
    const std::vector<bool> solved_flags = core::implicitly_solved_slots(*scene.network);
    const auto islands = core::find_islands(*scene.network);
    REQUIRE(islands.size() == 1);
    island = islands.front();
    for (int e : island.states) {
      if (solved_flags[static_cast<std::size_t>(e)]) solved.push_back(e);
    }
    pattern = core::jacobian_pattern(*scene.network, island, solved);
  }
  scene::Scene scene;
  core::Island island;
  std::vector<int> solved;
  core::JacobianPattern pattern;
};

constexpr Eigen::Index kNever = 1 << 30;

}  // namespace

TEST_CASE(
    "jacobian pattern: a tower is a chain, coloured in three evaluations per unknown of a "
    "box however tall",
    "[implicit][jacobian]") {
  std::mt19937 rng(36);
  for (int count : {2, 5, 12, 30}) {
    const OneIsland one(tower(rng, count, 1e-3));
    const std::vector<int>& solved = one.solved;
    const core::JacobianPattern& pattern = one.pattern;
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

TEST_CASE(
    "jacobian pattern: a pile with a contact between every two bodies forms its columns on "
    "their stars, as the whole island does to Newton's tolerance, at a fraction of the cost",
    "[implicit][jacobian]") {
  std::mt19937 rng(3639);
  for (int count : {9, 14, 20}) {
    const double dt = count == 14 ? 1.0 / 240.0 : 1e-3;
    const std::string text = pile(rng, count, dt);
    INFO(count << " bodies, dt " << dt);
    // The pattern of the whole (structural) island: every body's colour has a star of its
    // contacts (with every other body: all of them move in it) and its floor.
    const OneIsland one(text);
    const core::JacobianPattern& pattern = one.pattern;
    CHECK(pattern.groups.size() == static_cast<std::size_t>(13 * count));
    int starred_groups = 0;
    for (std::size_t g = 0; g < pattern.groups.size(); ++g) {
      if (pattern.group_star[g] < 0) continue;
      ++starred_groups;
      const core::Island& star = pattern.stars[static_cast<std::size_t>(pattern.group_star[g])];
      CHECK(static_cast<double>(star.states.size()) <=
            core::kStarShare * static_cast<double>(one.island.states.size()));
      CHECK(star.admittances.size() == static_cast<std::size_t>(count));
    }
    // Measured, in state entries: with 9 bodies a sphere's star holds 25% of the island, a
    // box's (its contacts are one per corner) 51%, over kStarShare; with 14 and 20 bodies
    // every star is under it (at most 33% and 24%).
    CHECK(starred_groups >= 13 * ((count + 1) / 2));
    if (count >= 14) CHECK(starred_groups == 13 * count);
    // Structural islands (every pair kept in the island, apart or not) and 0.1 s: bodies
    // hit the floor and one another. The same steps, to Newton's tolerance.
    const Run whole = run(text, dt, 0.1, true, 128, false, false);
    const Run starred = run(text, dt, 0.1, true, 128, true, false);
    REQUIRE(whole.x.allFinite());
    REQUIRE(starred.x.allFinite());
    const double scale = whole.x.cwiseAbs().maxCoeff();
    INFO("largest difference " << (starred.x - whole.x).cwiseAbs().maxCoeff() << " of " << scale
                               << "; matrices " << starred.matrices << " and " << whole.matrices
                               << "; evaluations " << starred.whole_evaluations << " and "
                               << whole.whole_evaluations);
    CHECK((starred.x - whole.x).cwiseAbs().maxCoeff() <= 1e-10 * scale);
    // Each matrix: 13 count columns, each evaluated twice on a star or once on the island;
    // the total counts the Newton iterations (whole island) too.
    // Measured: 0.76 of the evaluations with 9 bodies, 0.28 with 14, 0.38 with 20 (in both,
    // the same matrices and the same end state to the bit: a pair that is apart adds zero).
    CHECK(static_cast<double>(starred.whole_evaluations) <
          (count < 14 ? 0.8 : 0.5) * static_cast<double>(whole.whole_evaluations));
  }
}

TEST_CASE(
    "jacobian pattern: an arm of 40 links with LuGre friction at every joint uses no star: "
    "each would hold the whole arm, and cost more than the island",
    "[implicit][jacobian]") {
  // A scene as a user would write it: a planar arm of random links, a LuGre element (whose
  // state is solved, unlike a clamped friction's) at every joint: 40 elements, an island
  // large enough for stars. A LuGre state's column changes only its element and the arm,
  // but that star holds the arm's 80 state entries of the island's 120; evaluated twice it
  // cost 11434 evaluations against the island's 10315 (same end state to 1.7e-15) when stars
  // were chosen by their share of the elements. By their share of the state entries, none
  // is used, and the run is the island's to the bit.
  std::mt19937 rng(4036);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<>(lo, hi)(rng);
  };
  const int links = 40;
  std::ostringstream text;
  text.precision(17);
  text << "name = \"arm\"\ngravity = [0.0, -9.81, 0.0]\n[simulation]\nintegrator = "
          "\"implicit\"\ndt = 1e-3\nduration = 0.2\n[bodies.arm]\ntype = \"planar_arm\"\nlinks = "
          "[\n";
  for (int i = 0; i < links; ++i) {
    text << "  { length = " << uniform(0.05, 0.15)
         << ", width = 0.02, mass = " << uniform(0.05, 0.3) << " },\n";
  }
  text << "]\n";
  for (int i = 0; i < links; ++i) {
    text << "[impedances.joint" << i
         << "_friction]\ntype = \"lugre\"\nbody = \"arm\"\njoint = " << i
         << "\nstiffness = " << uniform(1e3, 1e4) << "\ndamping = " << uniform(0.5, 2.0)
         << "\nforce_limit = " << uniform(0.05, 0.5) << "\nstick_threshold = 0.02\n";
  }
  const OneIsland one(text.str());
  REQUIRE(one.island.impedances.size() >= core::kStarElements);
  for (std::size_t g = 0; g < one.pattern.groups.size(); ++g) CHECK(one.pattern.group_star[g] < 0);
  const Run starred = run(text.str(), 1e-3, 0.1, true, 128, true);
  const Run whole = run(text.str(), 1e-3, 0.1, true, 128, false);
  REQUIRE(whole.x.allFinite());
  REQUIRE(starred.x.allFinite());
  INFO("largest difference " << (starred.x - whole.x).cwiseAbs().maxCoeff() << "; evaluations "
                             << starred.whole_evaluations << " and " << whole.whole_evaluations);
  CHECK((starred.x - whole.x).cwiseAbs().maxCoeff() == 0.0);
  CHECK(starred.whole_evaluations == whole.whole_evaluations);
}
