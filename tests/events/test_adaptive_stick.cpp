// rk4_adaptive on the sphere started at rest on the surface while sliding (no bounce): the
// stick time within 0.1% of the closed form v0 / ((1 + M R^2 / J) mu g) and the rolling
// speed v0 / (1 + J / (M R^2)) within 1e-6 relative, at every tolerance 1e-4 .. 1e-8, solid
// and hollow, for several (v0, mu, M, R). The rolling speed is exact in the model (angular
// momentum about the contact point is conserved, and RK4 keeps linear invariants), so any
// residual slip left by a step across the stick shows in it. The cost is printed.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "../physics/sphere_fixture.hpp"

using namespace stiction;
using testing::SphereCase;

TEST_CASE("rk4_adaptive: a sliding sphere sticks on time at every tolerance", "[adaptive]") {
  struct Variant {
    double v0, mu, mass, radius;
  };
  const Variant variants[] = {{2.0, 0.1, 0.3, 0.2}, {1.0, 0.3, 1.0, 0.1}, {3.0, 0.2, 2.0, 0.5}};
  for (double factor : {0.4, 2.0 / 3.0}) {
    for (const Variant& v : variants) {
      SphereCase c;
      c.inertia_factor = factor;
      c.v0 = v.v0;
      c.mu = v.mu;
      c.mass = v.mass;
      c.radius = v.radius;
      c.height = testing::resting_height(c);
      const double expected = c.v0 / ((1.0 + 1.0 / factor) * c.mu * c.g);
      const double rolling = c.v0 / (1.0 + factor);
      for (double tolerance : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
        auto net = testing::make_sphere(c);
        core::RunOptions options;
        options.integrator = "rk4_adaptive";
        options.dt = 1e-4;
        options.tolerance = tolerance;
        options.duration = expected + 0.3;
        const core::RunResult r = core::simulate(*net, options);
        REQUIRE_FALSE(r.instability);
        const double stick = testing::first_stick_time(r);
        const auto& tr = r.trajectory;
        const double speed = tr.at(tr.row_count() - 1, *tr.find("sphere.v.x"));
        std::printf(
            "%s v0 %g mu %g M %g R %g tol %g: stick %.7f s (closed form %.7f, %+.1e), "
            "rolling %+.1e, %ld steps, %ld evaluations\n",
            factor < 0.5 ? "solid " : "hollow", v.v0, v.mu, v.mass, v.radius, tolerance, stick,
            expected, stick / expected - 1.0, speed / rolling - 1.0, r.steps, r.evaluations);
        INFO("factor " << factor << " v0 " << v.v0 << " mu " << v.mu << " M " << v.mass << " R "
                       << v.radius << " tolerance " << tolerance);
        CHECK(stick == Approx(expected).epsilon(1e-3));
        CHECK(speed == Approx(rolling).epsilon(1e-6));
      }
    }
  }
}
