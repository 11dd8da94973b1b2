// Kikuuwe friction (eq. 19) and contact (eqs. 23-24): exact stiction, saturation and sign.
#include <catch2/catch.hpp>

#include "components/admittance/point_mass.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "components/impedance/kikuuwe_friction.hpp"
#include "components/maps/contact_point_map.hpp"
#include "core/simulation.hpp"

using namespace stiction;
using components::KikuuweFriction;
using components::KikuuweFrictionParams;
using core::Vec;

TEST_CASE("unsaturated friction: the state derivative equals the input velocity exactly",
          "[friction]") {
  KikuuweFriction friction("j", {5000.0, 1.0, 0.5, 1});
  Vec u(1), e_dot(1), x_hat(2), e(1);
  for (double v : {1e-12, -3e-7, 1e-5, 2.5e-5}) {
    for (double tau : {0.0, 5e-5, 1e-4}) {
      x_hat << 0.3, v;
      e << 1e-5;
      friction.evaluate(0.0, x_hat, e, tau, u, e_dot);
      REQUIRE(std::abs(u[0]) < 0.5);
      CHECK(e_dot[0] == v);  // bit for bit
    }
  }
}

TEST_CASE("saturated friction: force magnitude F along (B + tau K) v + K e", "[friction]") {
  KikuuweFrictionParams p{5000.0, 1.0, 0.5, 2};
  KikuuweFriction friction("f", p);
  Vec x_hat(4), e(2), u(2), e_dot(2);
  x_hat << 0, 0, 3.0, -4.0;
  e << 0.0, 0.0;
  const double tau = 1e-4;
  friction.evaluate(0.0, x_hat, e, tau, u, e_dot);
  CHECK(u.norm() == Approx(0.5));
  CHECK(u[0] / u[1] == Approx(-0.75));
  // eps = (f - K e) / (B + tau K)
  CHECK(e_dot[0] == Approx(u[0] / (1.0 + tau * 5000.0)));
  // Friction on the body (-u) opposes its velocity.
  CHECK(-u.dot(x_hat.tail<2>()) < 0.0);
}

TEST_CASE("a block sliding on a flat contact decelerates at mu g and then stays put",
          "[friction][contact]") {
  using namespace components;
  for (double vx : {1.0, -0.7}) {
    core::Network net;
    PointMassParams pm;
    pm.mass = 2.0;
    const double K = 1e6;
    pm.position = core::Vec3(0, 0, -pm.mass * 9.8 / K);
    pm.velocity = core::Vec3(vx, 0.5 * vx, 0);
    auto mass = std::make_unique<PointMass>("block", pm);
    const auto& mass_ref = *mass;
    net.add_admittance(std::move(mass));
    KikuuweContactParams cp;
    cp.stiffness = K;
    cp.damping = 2000.0;
    cp.mu = 0.4;
    net.add_impedance(std::make_unique<KikuuweContact>("ground", cp),
                      std::make_unique<ContactPointMap>(mass_ref, 0.0, cp.normal));
    net.finalize();
    core::RunOptions options;
    options.dt = 1e-4;
    options.duration = 1.0;
    const auto r = core::simulate(net, options);
    REQUIRE_FALSE(r.instability);
    const auto& tr = r.trajectory;
    // Speed after 0.1 s: |v0| - mu g t along the initial direction.
    const double speed0 = std::hypot(vx, 0.5 * vx);
    const int row = 100;
    const double speed = std::hypot(tr.at(row, *tr.find("block.v.x")), tr.at(row, *tr.find("block.v.y")));
    CHECK(speed == Approx(speed0 - 0.4 * 9.8 * 0.1).epsilon(1e-3));
    // Direction is kept: friction acts exactly against the velocity.
    CHECK(tr.at(row, *tr.find("block.v.y")) / tr.at(row, *tr.find("block.v.x")) == Approx(0.5));
    // Stopped at the end, where the slide of length v0^2 / (2 mu g) ends.
    const int last = tr.row_count() - 1;
    CHECK(std::abs(tr.at(last, *tr.find("block.v.x"))) < 1e-6);
    const double travel = std::hypot(tr.at(last, *tr.find("block.p.x")), tr.at(last, *tr.find("block.p.y")));
    CHECK(travel == Approx(speed0 * speed0 / (2 * 0.4 * 9.8)).epsilon(2e-3));
  }
}
