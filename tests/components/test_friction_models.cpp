// Spring-damper (10), Dahl (11) and LuGre (12) impedances, on a 1-D slider defined here so
// that these tests depend on no other component.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <memory>

#include "components/impedance/dahl.hpp"
#include "components/impedance/lugre.hpp"
#include "components/impedance/spring_damper.hpp"
#include "core/admittance.hpp"
#include "core/coordinate_map.hpp"
#include "core/integrator.hpp"
#include "core/network.hpp"

using namespace stiction;

namespace {

// A mass on a line: state [x, v], input f. With `prescribed`, v stays at its initial value
// whatever the force (a velocity source), to drive an element at constant sliding speed.
class Slider final : public core::Admittance {
 public:
  Slider(double mass, double v0, bool prescribed)
      : core::Admittance("slider"), mass_(mass), v0_(v0), prescribed_(prescribed) {}
  std::string_view type() const override { return "slider"; }
  int state_size() const override { return 2; }
  int input_size() const override { return 1; }
  std::vector<std::string> state_labels() const override { return {"x", "v"}; }
  void initial_state(core::VecRef x) const override { x << 0.0, v0_; }
  void derivative(core::ConstVecRef x, core::ConstVecRef u_hat, core::VecRef x_dot) const override {
    x_dot[0] = x[1];
    x_dot[1] = prescribed_ ? 0.0 : u_hat[0] / mass_;
  }
  std::vector<core::SignalInfo> signals() const override { return {{"x", {}}, {"v", {}}}; }
  void write_signals(core::ConstVecRef x, core::VecRef out) const override { out = x; }
  double energy(core::ConstVecRef x) const override { return 0.5 * mass_ * x[1] * x[1]; }

 private:
  double mass_, v0_;
  bool prescribed_;
};

// x_hat = [x, v]; the slider receives -u (DESIGN section 1), as a joint map does.
class SliderMap final : public core::CoordinateMap {
 public:
  explicit SliderMap(const Slider& s) : slider_(s) {}
  int motion_size() const override { return 2; }
  int force_size() const override { return 1; }
  std::vector<const core::Admittance*> admittances() const override { return {&slider_}; }
  void bind(const std::vector<core::Slot>& slots) override { slot_ = slots.at(0); }
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override {
    x_hat = x.segment(slot_.state_offset, 2);
  }
  void apply(core::ConstVecRef, core::ConstVecRef u, core::VecRef u_hat) const override {
    u_hat[slot_.input_offset] -= u[0];
  }

 private:
  const Slider& slider_;
  core::Slot slot_;
};

// A prescribed external force f(t) on the slider: u = -f(t), so the slider receives +f.
class ForceSource final : public core::Impedance {
 public:
  explicit ForceSource(std::function<double(double)> f)
      : core::Impedance("push"), f_(std::move(f)) {}
  std::string_view type() const override { return "force_source"; }
  int input_size() const override { return 2; }
  int output_size() const override { return 1; }
  void evaluate(double t, core::ConstVecRef, core::ConstVecRef, double, core::VecRef u,
                core::VecRef) const override {
    u[0] = -f_(t);
  }
  std::vector<core::SignalInfo> signals() const override { return {{"f", {}}}; }
  void write_signals(core::ConstVecRef, core::ConstVecRef, core::ConstVecRef u,
                     core::VecRef out) const override {
    out[0] = -u[0];
  }

 private:
  std::function<double(double)> f_;
};

// A slider with one friction element (and optionally a push); the element is impedance 0.
struct Rig {
  core::Network net;
  core::Vec x;
  std::unique_ptr<core::RungeKuttaStepper> stepper;
  double t = 0.0;
  const Slider* slider = nullptr;

  Rig(double mass, double v0, bool prescribed, std::unique_ptr<core::Impedance> element,
      std::function<double(double)> push = {}) {
    auto s = std::make_unique<Slider>(mass, v0, prescribed);
    slider = s.get();
    net.add_admittance(std::move(s));
    net.add_impedance(std::move(element), std::make_unique<SliderMap>(*slider));
    if (push)
      net.add_impedance(std::make_unique<ForceSource>(push), std::make_unique<SliderMap>(*slider));
    net.finalize();
    x = net.initial_state();
    stepper = std::make_unique<core::RungeKuttaStepper>(core::rk4_tableau(), net.state_dim());
  }
  void run(double duration, double dt = 1e-4) {
    const long steps = std::lround(duration / dt);
    for (long k = 0; k < steps; ++k, t += dt) stepper->step(net, t, dt, x);
  }
  double position() const { return x[0]; }
  double velocity() const { return x[1]; }
  double e() const { return x[2]; }
  // Output u of the friction element (impedance 0) at the current state.
  double element_output() {
    const auto& imp = *net.impedances()[0];
    core::Vec x_hat(2), u(1), y_dot(1);
    net.map_of(0).motion(x, x_hat);
    imp.evaluate(t, x_hat, x.segment(2, 1), 1e-4, u, y_dot);
    return u[0];
  }
  // Force the slider receives from everything, as the network applies it.
  double force_on_slider() {
    core::Vec x_dot(net.state_dim());
    net.derivative(t, x, 1e-4, x_dot);
    return x_dot[1];  // with mass 1
  }
};

}  // namespace

TEST_CASE("spring-damper: u = K (p - rest) + B v exactly", "[spring_damper]") {
  components::SpringDamperParams p;
  p.stiffness = 1234.5;
  p.damping = 6.75;
  p.dimension = 3;
  components::SpringDamper sd("sd", p);
  core::Vec x_hat(6), u(3), y(0), y_dot(0);
  x_hat << 0.1, -0.02, 0.3, 1.5, -2.0, 0.25;
  sd.evaluate(0.0, x_hat, y, 1e-4, u, y_dot);
  for (int i = 0; i < 3; ++i) CHECK(u[i] == 1234.5 * x_hat[i] + 6.75 * x_hat[3 + i]);
  core::Vec out(3);
  sd.write_signals(x_hat, y, u, out);
  CHECK(out == -u);  // the force on the moving side
  CHECK(sd.stored_energy(x_hat, y) == Approx(0.5 * 1234.5 * (0.01 + 0.0004 + 0.09)));
  REQUIRE(sd.signals().size() == 1);
  CHECK(sd.signals()[0].name == "f");
  CHECK(sd.signals()[0].axes == core::xyz_axes());

  p.rest = core::Vec(3);
  p.rest << 0.0, 0.0, 0.3;
  components::SpringDamper with_rest("sd", p);
  with_rest.evaluate(0.0, x_hat, y, 1e-4, u, y_dot);
  CHECK(u[2] == 1234.5 * (0.3 - 0.3) + 6.75 * 0.25);
  CHECK(u[0] == 1234.5 * 0.1 + 6.75 * 1.5);

  components::SpringDamperParams q;
  q.dimension = 1;
  components::SpringDamper scalar("sd1", q);
  CHECK(scalar.signals()[0].name == "tau");
  CHECK(scalar.signals()[0].axes.empty());
}

TEST_CASE("spring-damper: a mass on it oscillates at sqrt(K/m)", "[spring_damper]") {
  // Sign check through the network: the spring pulls the mass back, so it oscillates
  // (a wrong sign would make it run away exponentially).
  components::SpringDamperParams p;
  p.stiffness = 100.0;
  p.damping = 0.0;
  p.dimension = 1;
  Rig rig(1.0, 1.0, false, std::make_unique<components::SpringDamper>("sd", p));
  const double period = 2 * M_PI / 10.0;
  rig.run(period / 4, period / 4000);
  INFO("x at a quarter period " << rig.position() << ", v " << rig.velocity());
  CHECK(rig.position() == Approx(0.1).epsilon(1e-6));
  CHECK(std::abs(rig.velocity()) < 1e-6);
}

TEST_CASE("dahl: sliding at constant speed reaches the force level F", "[dahl]") {
  components::DahlParams p;
  p.stiffness = 1e4;
  p.force_limit = 0.8;
  for (double v : {0.1, -0.05}) {
    Rig rig(1.0, v, true, std::make_unique<components::Dahl>("dahl", p));
    // e relaxes at rate |v| K / F = 1250/s or 625/s: 0.1 s is 60+ time constants.
    rig.run(0.1);
    INFO("v = " << v << ": u = " << rig.element_output() << ", e = " << rig.e());
    CHECK(rig.element_output() == Approx(std::copysign(0.8, v)).epsilon(1e-9));
    CHECK(rig.e() == Approx(std::copysign(0.8 / 1e4, v)).epsilon(1e-9));
  }
}

// A 1 kg body launched at 0.5 m/s against friction of level F = 1 N: while sliding the
// force on it opposes v and is already close to -F; the Coulomb deceleration F/m = 1 m/s^2
// stops it near t = 0.5 s, after v0^2 / (2 F/m), leaving only a small pre-sliding oscillation.
static void check_slides_to_rest(Rig& rig) {
  rig.run(0.05);
  CHECK(rig.velocity() > 0.0);
  CHECK(rig.velocity() < 0.5);
  CHECK(rig.force_on_slider() < -0.99);
  rig.run(0.95);
  INFO("v(1 s) = " << rig.velocity() << ", x(1 s) = " << rig.position());
  CHECK(std::abs(rig.velocity()) < 0.02);
  CHECK(rig.position() == Approx(0.125).epsilon(0.02));
}

TEST_CASE("dahl: friction decelerates a sliding body to rest", "[dahl]") {
  components::DahlParams p;
  p.stiffness = 1e4;
  p.force_limit = 1.0;
  Rig rig(1.0, 0.5, false, std::make_unique<components::Dahl>("dahl", p));
  check_slides_to_rest(rig);
}

TEST_CASE("lugre: sliding at constant speed gives F + D v, and the Stribeck curve", "[lugre]") {
  components::LuGreParams p;
  p.stiffness = 1e4;
  p.damping = 2.0;
  p.viscous = 0.3;
  p.force_limit = 0.5;
  {
    Rig rig(1.0, 0.2, true, std::make_unique<components::LuGre>("lugre", p));
    rig.run(0.1);  // relaxation rate |v| K / F = 4000/s
    INFO("u = " << rig.element_output() << ", e = " << rig.e());
    CHECK(rig.element_output() == Approx(0.5 + 0.3 * 0.2).epsilon(1e-9));
  }
  {
    Rig rig(1.0, -0.2, true, std::make_unique<components::LuGre>("lugre", p));
    rig.run(0.1);
    CHECK(rig.element_output() == Approx(-(0.5 + 0.3 * 0.2)).epsilon(1e-9));
  }
  // Stribeck: at v = vs the steady level is F + (Fs - F) / e.
  p.static_limit = 0.8;
  p.stribeck_velocity = 0.2;
  p.viscous = 0.0;
  components::LuGre lugre("s", p);
  CHECK(lugre.steady_deflection(0.0) * p.stiffness == Approx(0.8));
  CHECK(lugre.steady_deflection(1e3) * p.stiffness == Approx(0.5));
  Rig rig(1.0, 0.2, true, std::make_unique<components::LuGre>("lugre", p));
  rig.run(0.1);
  CHECK(rig.element_output() == Approx(0.5 + 0.3 * std::exp(-1.0)).epsilon(1e-9));
}

TEST_CASE("lugre: friction decelerates a sliding body", "[lugre]") {
  components::LuGreParams p;
  p.stiffness = 1e4;
  p.damping = 20.0;
  p.force_limit = 1.0;
  Rig rig(1.0, 0.5, false, std::make_unique<components::LuGre>("lugre", p));
  check_slides_to_rest(rig);
}

TEST_CASE("lugre: drifts under a sub-Coulomb dithering force, e keeps changing", "[lugre]") {
  // The paper's torque shape (28c) after t = 4 s: 0.336 + 0.144 sin(100 t) peaks at
  // 0.48 < F = 0.5, so a Coulomb model holds the body still. LuGre lets it creep: each
  // cycle moves the bristle anchor (x - e) a little, without bound. Parameters of
  // Simulation II's joints (K = 5000, B = 1, F = 0.5) on a 0.01 kg m^2-like inertia.
  components::LuGreParams p;
  p.stiffness = 5000.0;
  p.damping = 1.0;
  p.force_limit = 0.5;
  auto push = [](double t) { return 0.336 + 0.144 * std::sin(100.0 * t); };
  Rig rig(0.01, 0.0, false, std::make_unique<components::LuGre>("lugre", p), push);
  rig.run(1.0);
  const double anchor1 = rig.position() - rig.e();
  const double e1 = rig.e();
  rig.run(1.0);
  const double anchor2 = rig.position() - rig.e();
  const double e2 = rig.e();
  rig.run(1.0);
  const double anchor3 = rig.position() - rig.e();
  INFO("anchor x - e at 1, 2, 3 s: " << anchor1 << ", " << anchor2 << ", " << anchor3
                                     << "; e(1 s) = " << e1 << ", e(2 s) = " << e2);
  // Not a transient that settles: the drift per second stays of the same size.
  CHECK(anchor2 - anchor1 > 1e-3);
  CHECK(anchor3 - anchor2 > 0.5 * (anchor2 - anchor1));
  // The force never reached F, yet the body travelled far beyond the elastic range F/K.
  CHECK(rig.position() > 20 * p.force_limit / p.stiffness);
}

TEST_CASE("lugre: a sub-Coulomb step force slides the anchor before it settles", "[lugre]") {
  // Under a constant force below F, LuGre does come to rest, but only after the bristle
  // anchor (x - e) has slid many elastic ranges F/K; eq. (19) keeps the anchor fixed while
  // the force stays below F (eps == v). Same parameters as the dithering case.
  components::LuGreParams p;
  p.stiffness = 5000.0;
  p.damping = 1.0;
  p.force_limit = 0.5;
  Rig rig(0.01, 0.0, false, std::make_unique<components::LuGre>("lugre", p),
          [](double) { return 0.48; });
  rig.run(2.0);
  const double anchor2 = rig.position() - rig.e();
  rig.run(1.0);
  const double anchor3 = rig.position() - rig.e();
  INFO("anchor x - e at 2 s: " << anchor2 << " (F/K = " << p.force_limit / p.stiffness
                               << "), change over the next second " << anchor3 - anchor2);
  CHECK(anchor2 > 10 * p.force_limit / p.stiffness);
  CHECK(std::abs(anchor3 - anchor2) < 1e-9);
  CHECK(rig.e() == Approx(0.48 / p.stiffness).epsilon(1e-6));  // at rest: K e holds the push
}
