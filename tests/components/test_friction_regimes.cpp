// Every element whose friction is Kikuuwe's law tells the event detector its regime (the
// ClampedFriction capability), so that a stick is timed when the law holds, not when an
// elastic ringing inside the friction band decays below the stick threshold. For each such
// element type: generated spin-down (or slide-down) scenes, written as scene files, whose
// first stick must come within one step of the closed form J w0 / F (m v0 / F, v0 / (mu g)).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/capabilities.hpp"
#include "core/simulation.hpp"
#include "scene/scene.hpp"

using namespace stiction;

namespace {

// Impedance types whose friction is Kikuuwe's law (19): each must be a ClampedFriction.
const std::set<std::string> kKikuuweTypes{"kikuuwe_contact", "kikuuwe_friction", "penalty_joint"};
// Friction with a law of its own (a bristle model that never holds exactly): no regime.
const std::set<std::string> kOtherFrictionTypes{"lugre", "dahl"};
// No friction at all.
const std::set<std::string> kFrictionlessTypes{"spring_damper", "torque_source", "force_source"};
// The element comes from the program that loads the scene (scene/external_elements.hpp): its
// law, friction or not, is the program's; its regimes come from its own slip velocity.
const std::set<std::string> kSuppliedInCodeTypes{"external"};

scene::Scene from_text(const std::string& text) {
  return scene::build_scene(toml::parse(std::string_view(text), std::string_view("gen.toml")),
                            "gen.toml");
}

// The impedance types the scene loader knows, as its error for an unknown type lists them:
// the registry itself, so that a type added later is seen here.
std::vector<std::string> registered_impedance_types() {
  const char* probe = R"(
[bodies.b]
type = "point_mass"
mass = 1.0
[impedances.x]
type = "no_such_type"
body = "b"
)";
  try {
    from_text(probe);
  } catch (const scene::InputError& e) {
    const std::string message = e.what();
    const std::string marker = "expected one of ";
    const auto begin = message.find(marker);
    REQUIRE(begin != std::string::npos);
    const auto end = message.find(')', begin);
    std::stringstream list(message.substr(begin + marker.size(), end - begin - marker.size()));
    std::vector<std::string> types;
    for (std::string item; std::getline(list, item, ',');) {
      item.erase(0, item.find_first_not_of(' '));
      types.push_back(item);
    }
    return types;
  }
  FAIL("an unknown impedance type was accepted");
  return {};
}

struct Case {
  std::string type;       // the impedance type under test
  std::string element;    // the element whose stick is timed
  std::string text;       // the scene file
  double expected = 0.0;  // closed-form stick time
  double dt = 0.0;
};

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

std::string number(double x) {
  std::ostringstream out;
  out.precision(17);
  out << std::scientific << x;
  return out.str();
}

std::string simulation(double dt, double duration) {
  return "[simulation]\nintegrator = \"rk4\"\ndt = " + number(dt) +
         "\nduration = " + number(duration) + "\noutput_rate = 100.0\n";
}

using Rng = std::mt19937;
double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
Eigen::Vector3d random_unit(Rng& rng) {
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  } while (v.norm() < 0.2 || v.norm() > 1.0);
  return v.normalized();
}
Eigen::Vector3d random_tangent(Rng& rng, const Eigen::Vector3d& normal) {
  Eigen::Vector3d t;
  do {
    const Eigen::Vector3d v = random_unit(rng);
    t = v - normal.dot(v) * normal;
  } while (t.norm() < 0.2);
  return t.normalized();
}

// A one-link arm about a random axis, gravity off, spinning at w0 on a kikuuwe_friction joint:
// J = m L^2 / 3 about the joint (a thin link, com at L / 2), stops at J w0 / F.
Case arm_joint(Rng& rng) {
  const double m = uniform(rng, 0.1, 2.0), L = uniform(rng, 0.1, 1.0);
  const double J = m * L * L / 3.0;
  const double w0 = uniform(rng, 1.0, 10.0) * (rng() % 2 ? 1.0 : -1.0);
  const double stop = uniform(rng, 0.2, 1.2);
  const double F = J * std::abs(w0) / stop;
  const double dt = uniform(rng, 5e-5, 5e-4);
  // The stuck spring's frequency sqrt(K / J) well inside RK4's limit, lightly damped.
  const double K = J * std::pow(uniform(rng, 0.05, 0.5) / dt, 2);
  const double B = 2.0 * uniform(rng, 0.05, 0.5) * std::sqrt(K * J);
  Case c{"kikuuwe_friction", "joint", "", J * std::abs(w0) / F, dt};
  c.text = "gravity = [0.0, 0.0, 0.0]\n" + simulation(dt, stop + 0.3) +
           "[bodies.arm]\ntype = \"planar_arm\"\naxis = " + vec(random_unit(rng)) +
           "\nlinks = [{ length = " + number(L) + ", mass = " + number(m) + " }]\nrates = [" +
           number(w0) + "]\n[impedances.joint]\ntype = \"kikuuwe_friction\"\n" +
           "body = \"arm\"\njoint = 0\nstiffness = " + number(K) + "\ndamping = " + number(B) +
           "\nforce_limit = " + number(F) + "\n";
  return c;
}

// A point mass sliding in a random direction, gravity off, on a point-wired
// kikuuwe_friction to the world: stops at m v0 / F.
Case point_friction(Rng& rng) {
  const double m = uniform(rng, 0.1, 5.0), v0 = uniform(rng, 0.5, 5.0);
  const double stop = uniform(rng, 0.2, 1.2);
  const double F = m * v0 / stop;
  const double dt = uniform(rng, 5e-5, 5e-4);
  const double K = m * std::pow(uniform(rng, 0.05, 0.5) / dt, 2);
  const double B = 2.0 * uniform(rng, 0.05, 0.5) * std::sqrt(K * m);
  Case c{"kikuuwe_friction", "drag", "", m * v0 / F, dt};
  c.text = "gravity = [0.0, 0.0, 0.0]\n" + simulation(dt, stop + 0.3) +
           "[bodies.puck]\ntype = \"point_mass\"\nmass = " + number(m) +
           "\nvelocity = " + vec(v0 * random_unit(rng)) +
           "\n[impedances.drag]\ntype = \"kikuuwe_friction\"\n" +
           "body = \"puck\"\nstiffness = " + number(K) + "\ndamping = " + number(B) +
           "\nforce_limit = " + number(F) + "\n";
  return c;
}

// A point mass settled on a surface of random normal (gravity against it, g random):
// launched along the surface at v0, it stops at v0 / (mu g). With a belt instead (a moving
// surface), the mass starts at rest and sticks once it moves with the belt: vb / (mu g).
Case contact(Rng& rng, bool belt) {
  const double m = uniform(rng, 0.1, 5.0), g = uniform(rng, 3.0, 20.0);
  const double mu = uniform(rng, 0.1, 1.0), stop = uniform(rng, 0.2, 1.2);
  const double v0 = mu * g * stop;
  const double dt = uniform(rng, 5e-5, 3e-4);
  const double K = m * std::pow(uniform(rng, 0.05, 0.5) / dt, 2);
  const double B = 2.0 * uniform(rng, 0.05, 0.5) * std::sqrt(K * m);
  const Eigen::Vector3d n = random_unit(rng), t = random_tangent(rng, n);
  const double offset = uniform(rng, -2.0, 2.0);
  Case c{"kikuuwe_contact", "floor", "", v0 / (mu * g), dt};
  c.text = "gravity = " + vec(-g * n) + "\n" + simulation(dt, stop + 0.3) +
           "[bodies.puck]\ntype = \"point_mass\"\nmass = " + number(m) +
           "\nposition = " + vec(offset * n) + "\nvelocity = " +
           vec(belt ? Eigen::Vector3d(Eigen::Vector3d::Zero()) : Eigen::Vector3d(v0 * t)) +
           "\n[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"puck\"\nnormal = " + vec(n) +
           "\noffset = " + number(offset) + "\nstiffness = " + number(K) +
           "\ndamping = " + number(B) + "\nmu = " + number(mu) + "\nsettle = true\n" +
           (belt ? "belt_speed = " + number(v0) + "\nbelt_direction = " + vec(t) + "\n" : "");
  return c;
}

// Simulation III's joint 0 (scenes/two_link_penalty.toml): a box link pinned at one end to
// the ground by a penalty joint about the world z axis, gravity off, spinning at w0. Its
// moment about the joint is m (L^2 + w^2) / 12 + m (L / 2)^2; the centripetal force
// stretches the joint by m w0^2 L / (2 Ks) (< 1e-5 m here) along the link, which neither
// changes J measurably nor makes a moment. It stops at J w0 / F.
Case penalty_joint(Rng& rng) {
  const double m = uniform(rng, 0.2, 1.0), L = uniform(rng, 0.2, 0.5);
  const double w = uniform(rng, 0.02, 0.05);
  const double J = m * (L * L + w * w) / 12.0 + m * L * L / 4.0;
  const double w0 = uniform(rng, 1.0, 8.0) * (rng() % 2 ? 1.0 : -1.0);
  const double stop = uniform(rng, 0.2, 1.0);
  const double F = J * std::abs(w0) / stop;
  const double dt = uniform(rng, 3e-5, 1e-4);
  Case c{"penalty_joint", "pin", "", J * std::abs(w0) / F, dt};
  c.text = "gravity = [0.0, 0.0, 0.0]\n" + simulation(dt, stop + 0.3) +
           "[bodies.link]\ntype = \"rigid_body\"\nmass = " + number(m) +
           "\nshape = \"box\"\nsize = [" + number(L) + ", " + number(w) + ", " + number(w) +
           "]\nposition = [" + number(L / 2) + ", 0.0, 0.0]\nvelocity = [0.0, " +
           number(w0 * L / 2) + ", 0.0]\nangular_velocity = [0.0, 0.0, " + number(w0) +
           "]\n[impedances.pin]\ntype = \"penalty_joint\"\nbody = \"link\"\npoint = [" +
           number(-L / 2) + ", 0.0, 0.0]\nfriction_limit = " + number(F) + "\n";
  return c;
}

}  // namespace

TEST_CASE("friction regimes: every registered impedance type is classified") {
  const std::vector<std::string> types = registered_impedance_types();
  REQUIRE(types.size() >= 3);
  for (const std::string& type : types) {
    INFO(type << ": a new impedance type; if its friction is Kikuuwe's law it must be a "
                 "ClampedFriction and get a spin-down case here");
    const int classes = static_cast<int>(kKikuuweTypes.contains(type)) +
                        static_cast<int>(kOtherFrictionTypes.contains(type)) +
                        static_cast<int>(kFrictionlessTypes.contains(type)) +
                        static_cast<int>(kSuppliedInCodeTypes.contains(type));
    CHECK(classes == 1);
    // A name that says friction, contact or joint is never filed as frictionless.
    const bool sounds_frictional = type.find("friction") != std::string::npos ||
                                   type.find("contact") != std::string::npos ||
                                   type.find("joint") != std::string::npos;
    if (sounds_frictional) CHECK_FALSE(kFrictionlessTypes.contains(type));
  }
  for (const auto* known :
       {&kKikuuweTypes, &kOtherFrictionTypes, &kFrictionlessTypes, &kSuppliedInCodeTypes}) {
    for (const std::string& type : *known) {
      INFO(type);
      CHECK(std::find(types.begin(), types.end(), type) != types.end());
    }
  }
}

TEST_CASE("friction regimes: every Kikuuwe element sticks within one step of the closed form") {
  Rng rng(20261201);
  std::vector<Case> cases;
  for (int i = 0; i < 3; ++i) {
    cases.push_back(arm_joint(rng));
    cases.push_back(point_friction(rng));
    cases.push_back(contact(rng, false));
    cases.push_back(contact(rng, true));
    cases.push_back(penalty_joint(rng));
  }
  std::set<std::string> covered;
  for (const Case& c : cases) {
    INFO(c.type << " scene:\n" << c.text);
    scene::Scene s = from_text(c.text);
    // The element has the capability the event detector asks.
    bool found = false;
    for (int i = 0; i < static_cast<int>(s.network->impedances().size()); ++i) {
      const core::Impedance& imp = *s.network->impedances()[i];
      if (imp.name() != c.element) continue;
      found = true;
      CHECK(s.network->capabilities(i).friction != nullptr);
      CHECK(s.network->capabilities(i).slip != nullptr);
    }
    REQUIRE(found);
    const core::RunResult result = core::simulate(*s.network, s.run);
    REQUIRE_FALSE(result.instability.has_value());
    const auto history = std::find_if(result.slip_events.begin(), result.slip_events.end(),
                                      [&](const auto& h) { return h.component == c.element; });
    REQUIRE(history != result.slip_events.end());
    const double stick = history->monitor.stick_time();
    INFO("stick " << stick << " s, closed form " << c.expected << " s, dt " << c.dt << " s");
    CHECK(std::abs(stick - c.expected) <= c.dt);
    covered.insert(c.type);
  }
  CHECK(covered == kKikuuweTypes);
}
