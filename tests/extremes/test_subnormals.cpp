// A body that friction has brought to rest: its velocity and friction state decay
// geometrically towards zero. Without flushing, they pass through subnormal floats for
// thousands of steps (each operation tens of times slower on x86). The run flushes them:
// no value of the run is subnormal, and the mode of the calling thread is left as it was.
#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <random>
#include <string>

#include "core/simulation.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

bool subnormal(double v) { return v != 0.0 && std::abs(v) < DBL_MIN; }

}  // namespace

TEST_CASE("a puck at rest after sliding: no subnormal value in its run", "[extremes]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    const double mass = 0.5 + 3.0 * unit(rng), mu = 0.2 + 0.5 * unit(rng);
    const std::string text =
        "name = \"puck_at_rest\"\n[simulation]\ndt = 1e-4\nduration = 20.0\noutput_rate = 10.0\n"
        "[bodies.puck]\ntype = \"point_mass\"\nmass = " + std::to_string(mass) +
        "\nvelocity = [1.5, 0.5, 0.0]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\n"
        "body = \"puck\"\nstiffness = 1e5\ndamping = 900.0\nmu = " + std::to_string(mu) +
        "\nsettle = true\n";
    scene::Scene s = scene::build_scene(toml::parse(std::string_view(text), std::string_view("puck_at_rest.toml")), "puck_at_rest.toml");
    const core::RunResult result = core::simulate(*s.network, s.run);
    REQUIRE_FALSE(result.instability);
    int found = 0;
    for (std::size_t r = 0; r < static_cast<std::size_t>(result.trajectory.row_count()); ++r) {
      for (std::size_t c = 0; c < static_cast<std::size_t>(result.trajectory.column_count()); ++c) {
        if (subnormal(result.trajectory.at(static_cast<int>(r), static_cast<int>(c)))) ++found;
      }
    }
    INFO("mass " << mass << " kg, mu " << mu);
    CHECK(found == 0);
  }
  // The caller's arithmetic is untouched: a subnormal still comes out subnormal here.
  volatile double tiny = DBL_MIN;
  CHECK(subnormal(tiny / 16.0));
}
