// Scenes of every kind the energy monitor must judge (issue 26, item 2), generated with
// random parameters and odd orientations from a seed: a sphere with spin on a tilted plane,
// a box on a slope touching it at its corners, an arm swinging in a tilted plane against
// joint friction and a motor, a mass on a spring on a belt, and a block pushed across a
// floor by a time-driven force against a spring. `lift` raises every scene by that height
// (the monitor's bound must not depend on it).
#pragma once

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace stiction::testing {

struct EnergyScene {
  std::string kind;
  std::string toml;
};

inline const std::vector<std::string>& energy_scene_kinds() {
  static const std::vector<std::string> kinds = {"sphere", "box", "arm", "belt", "pushed"};
  return kinds;
}

// A plane through (0, 0, lift) with normal (sin a cos b, sin a sin b, cos a): its offset.
inline std::string plane(double a, double b, double lift, const std::string& extra = "") {
  std::ostringstream s;
  s.precision(17);
  const double n[3] = {std::sin(a) * std::cos(b), std::sin(a) * std::sin(b), std::cos(a)};
  s << "normal = [" << n[0] << ", " << n[1] << ", " << n[2] << "]\noffset = " << lift * n[2] << "\n"
    << extra;
  return s.str();
}

inline EnergyScene energy_scene(const std::string& kind, unsigned seed, double duration,
                                double lift = 0.0) {
  std::mt19937 rng(seed);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  const double deg = std::acos(-1.0) / 180.0;
  std::ostringstream s;
  s.precision(17);
  s << "name = \"" << kind << "_" << seed << "\"\ngravity = [0.0, 0.0, -9.8]\n"
    << "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = " << duration
    << "\noutput_rate = 200.0\n";
  if (kind == "sphere") {
    // Rolls or slides with spin on a plane tilted up to 8 degrees in a random direction.
    const double m = uniform(0.5, 8.0), r = uniform(0.05, 0.2), a = uniform(0.0, 8.0) * deg;
    const double b = uniform(0.0, 360.0) * deg;
    s << "[bodies.ball]\ntype = \"rigid_body\"\nmass = " << m
      << "\nshape = \"sphere\"\nradius = " << r << "\nposition = [0.0, 0.0, "
      << lift + r / std::cos(a) << "]\nvelocity = [" << uniform(-4.0, 4.0) << ", "
      << uniform(-4.0, 4.0) << ", 0.0]\nangular_velocity = [" << uniform(-30.0, 30.0) << ", "
      << uniform(-30.0, 30.0) << ", " << uniform(-5.0, 5.0)
      << "]\n[impedances.ground]\ntype = \"kikuuwe_contact\"\nbody = \"ball\"\n"
      << plane(a, b, lift) << "stiffness = " << uniform(1e6, 1e7)
      << "\ndamping = " << uniform(5.0, 50.0) << "\nmu = " << uniform(0.1, 0.5)
      << "\nsettle = true\n";
  } else if (kind == "box") {
    // Eight corner contacts on a slope of 5 to 30 degrees: slides down or sticks.
    const double m = uniform(0.3, 3.0), a = uniform(5.0, 30.0) * deg;
    const double K = uniform(3e5, 3e6);
    const double w = uniform(0.1, 0.3), d = uniform(0.1, 0.3), h = uniform(0.05, 0.2);
    s << "[bodies.box]\ntype = \"rigid_body\"\nmass = " << m << "\nshape = \"box\"\nsize = [" << w
      << ", " << d << ", " << h << "]\nposition = [" << std::sin(a) * h / 2 << ", 0.0, "
      << lift + std::cos(a) * h / 2 << "]\norientation = [" << std::cos(a / 2) << ", 0.0, "
      << std::sin(a / 2) << ", 0.0]\nvelocity = [" << uniform(-1.0, 1.0) << ", "
      << uniform(-1.0, 1.0) << ", 0.0]\nangular_velocity = [0.0, 0.0, " << uniform(-3.0, 3.0)
      << "]\n[impedances.slope]\ntype = \"kikuuwe_contact\"\nbody = \"box\"\n"
      << plane(a, 0.0, lift) << "stiffness = " << K
      << "\ndamping = " << 2.0 * std::sqrt(K * m / 4.0) << "\nmu = " << uniform(0.1, 0.7)
      << "\nsettle = true\n";
  } else if (kind == "arm") {
    // Two or three links in a plane tilted from the vertical: gravity swings them against
    // joint friction, and a motor drives the first joint.
    const int links = 2 + static_cast<int>(seed % 2);
    const double tilt = uniform(0.0, 60.0) * deg;
    s << "[bodies.arm]\ntype = \"planar_arm\"\nbase = [0.0, 0.0, " << lift << "]\naxis = [0.0, "
      << std::cos(tilt) << ", " << std::sin(tilt) << "]\nlinks = [\n";
    for (int i = 0; i < links; ++i) {
      s << "  { length = " << uniform(0.1, 0.3) << ", width = 0.02, mass = " << uniform(0.1, 0.5)
        << " },\n";
    }
    s << "]\nangles = [";
    for (int i = 0; i < links; ++i) s << (i ? ", " : "") << uniform(-1.5, 1.5);
    s << "]\nrates = [";
    for (int i = 0; i < links; ++i) s << (i ? ", " : "") << uniform(-3.0, 3.0);
    s << "]\n";
    for (int i = 0; i < links; ++i) {
      s << "[impedances.joint" << i << "_friction]\ntype = \"kikuuwe_friction\"\nbody = \"arm\"\n"
        << "joint = " << i << "\nstiffness = " << uniform(1e3, 1e4)
        << "\ndamping = " << uniform(0.1, 1.0) << "\nforce_limit = " << uniform(0.05, 0.4) << "\n";
    }
    s << "[impedances.motor]\ntype = \"torque_source\"\nbody = \"arm\"\njoint = 0\ntorque = \""
      << uniform(0.1, 0.5) << " * sin(" << uniform(2.0, 8.0) << " * t)\"\n";
  } else if (kind == "belt") {
    // A mass on a spring to a post, on a belt moving at a steady speed: stick-slip.
    const double m = uniform(0.3, 3.0), K = uniform(3e5, 3e6);
    s << "[bodies.mass]\ntype = \"point_mass\"\nmass = " << m << "\nposition = [0.0, 0.0, " << lift
      << "]\n[impedances.belt]\ntype = \"kikuuwe_contact\"\nbody = \"mass\"\n"
      << plane(0.0, 0.0, lift) << "belt_speed = " << uniform(0.05, 0.5)
      << "\nbelt_direction = [1.0, 0.0, 0.0]\nstiffness = " << K
      << "\ndamping = " << 2.0 * std::sqrt(K * m) << "\nmu = " << uniform(0.1, 0.6)
      << "\nsettle = true\n[impedances.spring]\ntype = \"spring_damper\"\nbody = \"mass\"\n"
      << "other_point = [0.0, 0.0, " << lift << "]\nstiffness = " << uniform(20.0, 400.0)
      << "\ndamping = 0.0\n";
  } else {  // pushed
    // A block pushed across a floor by a force that varies in time, held by a spring.
    const double m = uniform(0.3, 3.0), K = uniform(3e5, 3e6), f = uniform(1.0, 20.0);
    s << "[bodies.block]\ntype = \"point_mass\"\nmass = " << m << "\nposition = [0.0, 0.0, " << lift
      << "]\nvelocity = [" << uniform(-1.0, 1.0)
      << ", 0.0, 0.0]\n[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"block\"\n"
      << plane(0.0, 0.0, lift) << "stiffness = " << K << "\ndamping = " << 2.0 * std::sqrt(K * m)
      << "\nmu = " << uniform(0.1, 0.6) << "\nsettle = true\n"
      << "[impedances.push]\ntype = \"force_source\"\nbody = \"block\"\nforce = [\"" << f
      << " * (1 + sin(" << uniform(2.0, 10.0) << " * t))\", 0.0, 0.0]\n"
      << "[impedances.spring]\ntype = \"spring_damper\"\nbody = \"block\"\n"
      << "other_point = [0.0, 0.0, " << lift << "]\nstiffness = " << uniform(20.0, 400.0)
      << "\ndamping = " << uniform(0.0, 2.0) << "\n";
  }
  return {kind, s.str()};
}

}  // namespace stiction::testing
