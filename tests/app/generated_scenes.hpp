// Scenes written by the tests themselves (COMMON quality bar: not only scenes/): a six-link
// arm with joint friction and motors on every joint, a scene whose components have very long
// names, and a block sliding down a slope onto a floor (two contacts, stick and slip).
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace stiction::testing {

// n links of random length, joint friction and a motor per joint.
inline std::string arm_scene(int links, unsigned seed, double duration = 1.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> length(0.1, 0.25), torque(0.1, 0.6);
  std::ostringstream s;
  s << "name = \"arm" << links << "\"\ngravity = [0.0, 0.0, 0.0]\n"
    << "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = " << duration
    << "\noutput_rate = 500.0\n[bodies.arm]\ntype = \"planar_arm\"\nlinks = [\n";
  for (int i = 0; i < links; ++i) {
    s << "  { length = " << length(rng) << ", width = 0.02, mass = 0.2 },\n";
  }
  s << "]\n";
  for (int i = 0; i < links; ++i) {
    s << "[impedances.joint" << i << "_friction]\ntype = \"kikuuwe_friction\"\nbody = \"arm\"\n"
      << "joint = " << i << "\nstiffness = 5000.0\ndamping = 1.0\nforce_limit = 0.3\n"
      << "stick_threshold = 0.02\n"
      << "[impedances.motor" << i << "]\ntype = \"torque_source\"\nbody = \"arm\"\njoint = " << i
      << "\ntorque = \"" << torque(rng) << " * sin(" << 3 + i << " * t)\"\n";
  }
  return s.str();
}

// A sphere rolling on the ground, with component names far longer than a label has room for.
inline std::string long_names_scene(double duration = 0.8) {
  const std::string body = "a_sphere_with_a_really_quite_remarkably_long_component_name";
  const std::string ground = "the_ground_contact_element_whose_name_goes_on_and_on_forever";
  std::ostringstream s;
  s << "name = \"long_names\"\n[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = "
    << duration << "\noutput_rate = 500.0\n"
    << "[bodies." << body
    << "]\ntype = \"rigid_body\"\nmass = 0.3\nshape = \"sphere\"\nradius = 0.2\n"
    << "position = [0.0, 0.0, 0.2019]\nvelocity = [2.0, 0.0, 0.0]\n"
    << "[impedances." << ground << "]\ntype = \"kikuuwe_contact\"\nbody = \"" << body << "\"\n"
    << "stiffness = 1e7\ndamping = 10.0\nmu = 0.1\n";
  return s.str();
}

// A block on a 20 degree slope with mu = 0.2 (it slides) that reaches a flat floor (mu = 0.5,
// it sticks there): two contacts, the slope's and the floor's.
inline std::string slope_to_floor_scene(double duration = 1.5) {
  const double a = 20.0 * std::acos(-1.0) / 180.0;
  std::ostringstream s;
  s.precision(17);
  s << "name = \"slope_to_floor\"\ngravity = [0.0, 0.0, -9.8]\n"
    << "[simulation]\nintegrator = \"rk4\"\ndt = 1e-4\nduration = " << duration
    << "\noutput_rate = 500.0\n"
    << "[bodies.block]\ntype = \"point_mass\"\nmass = 1.0\n"
    << "position = [0.3, 0.0, " << 0.3 * std::tan(a) << "]\nvelocity = [0.0, 0.0, 0.0]\n"
    << "[impedances.slope]\ntype = \"kikuuwe_contact\"\nbody = \"block\"\n"
    << "normal = [" << -std::sin(a) << ", 0.0, " << std::cos(a) << "]\n"
    << "stiffness = 1e6\ndamping = 2000.0\nmu = 0.2\n"
    << "[impedances.floor]\ntype = \"kikuuwe_contact\"\nbody = \"block\"\n"
    << "normal = [0.0, 0.0, 1.0]\nstiffness = 1e6\ndamping = 2000.0\nmu = 0.5\n";
  return s.str();
}

inline std::filesystem::path write_scene(const std::filesystem::path& dir, const std::string& name,
                                         const std::string& text) {
  const std::filesystem::path path = dir / (name + ".toml");
  std::ofstream(path) << text;
  return path;
}

}  // namespace stiction::testing
