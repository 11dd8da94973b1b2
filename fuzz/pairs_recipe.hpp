// Builds a scene of bodies in contact with one another (issue 39 item 8) from fuzzer bytes
// (fuzz/fuzz_pairs.cpp): rigid spheres, hollow spheres and boxes, and now and then a shape a
// pair contact refuses (a cylinder, a point mass, a body with no shape), placed on a small
// grid so that they touch, overlap, sit one inside another or on the same point; pair
// contacts (`kikuuwe_contact` with `other`) between chosen bodies, between every two (the
// huge counts: up to 64 bodies, 2016 pairs), a body with itself or an unknown one; floors
// under some. Each number is either a plausible value or one from a pool of hostile TOML
// values (nan, inf, 1e308, 5e-324, -0.0, strings, arrays, nan-ish strings), so the scene
// builder, the pair geometry and the run loop meet them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz/toml_structure.hpp"

namespace stiction::fuzz {

namespace pairs {

inline constexpr std::string_view kHostile[] = {
    "nan",  "inf",   "-inf",    "1e308",   "-1e308",  "5e-324",    "-0.0",  "0.0",  "1e-300",
    "-1.0", "1e12",  "\"1.0\"", "\"nan\"", "\"NaN\"", "\"inf\"",   "[1.0]", "{}",   "true",
    "3",    "1e-12", "2e-308",  "1e200",   "\"1,5\"", "\"0x1p3\"", "+nan",  "-nan", "\"\""};

// How often a value is hostile, chosen per input (hostility()): a byte at or above this
// picks from the hostile pool. With every value hostile a scene is almost always refused
// and nothing steps; with none, the builder's checks go unvisited: a quarter of the inputs
// each way, and half in between.
inline int& hostile_from() {
  static int threshold = 256;
  return threshold;
}
inline void choose_hostility(ByteReader& in) {
  constexpr int kThresholds[] = {256, 252, 240, 192};
  hostile_from() = kThresholds[in.byte() % 4];
}

// A number: `plain` (TOML text), or one from the hostile pool.
inline std::string number(ByteReader& in, std::string_view plain) {
  const std::uint8_t b = in.byte();
  if (b < hostile_from()) return std::string(plain);
  return std::string(kHostile[b % std::size(kHostile)]);
}

// A coordinate on a grid of 5 cm (so that bodies of 5-20 cm touch and overlap), or hostile.
inline std::string coordinate(ByteReader& in) {
  const std::uint8_t b = in.byte();
  if (b < hostile_from()) return std::to_string((static_cast<int>(b % 9) - 4) * 5) + "e-2";
  return std::string(kHostile[b % std::size(kHostile)]);
}

inline std::string vec3(ByteReader& in) {
  const std::uint8_t b = in.byte();
  if (b >= hostile_from()) {
    if (b & 1) return "[1.0, 2.0]";                         // wrong length
    return std::string(kHostile[b % std::size(kHostile)]);  // not an array
  }
  return "[" + coordinate(in) + ", " + coordinate(in) + ", " + coordinate(in) + "]";
}

inline constexpr std::string_view kOrientations[] = {
    "[1.0, 0.0, 0.0, 0.0]", "[0.9, 0.1, -0.3, 0.2]", "[0.7, -0.2, 0.6, 0.1]",
    "[0.5, 0.5, 0.5, 0.5]", "[2.0, 0.0, 0.0, 0.0]",  "[0.0, 1.0, 0.0, 0.0]"};
inline constexpr std::string_view kOddOrientations[] = {
    "[0.0, 0.0, 0.0, 0.0]", "[nan, 0.0, 0.0, 0.0]", "[1e-300, 0.0, 0.0, 0.0]",
    "[1e300, 1e300, 0.0, 0.0]", "[1.0, 0.0, 0.0]"};

// From `good`, or from `odd` when the byte says hostile.
template <std::size_t N, std::size_t M>
std::string_view pick(ByteReader& in, const std::string_view (&good)[N],
                      const std::string_view (&odd)[M]) {
  const std::uint8_t b = in.byte();
  return b < hostile_from() ? good[b % N] : odd[b % M];
}

inline constexpr std::string_view kIntegrators[] = {
    "\"rk4\"",      "\"rk4\"",          "\"euler\"",  "\"heun\"",   "\"symplectic_euler\"",
    "\"implicit\"", "\"rk4_adaptive\"", "\"sdirk2\"", "\"sdirk4\"", "\"rk4\""};

inline constexpr std::string_view kSteps[] = {"1e-4", "1e-5", "1e-3", "0.016666666666666666",
                                              "1e-6", "0.1",  "1e-4", "2e-4"};

// PREFIX followed by the number i (appended: GCC 12 warns falsely on "b" + to_string(i)).
inline std::string named(std::string_view prefix, std::size_t i) {
  std::string s(prefix);
  s.append(std::to_string(i));
  return s;
}

}  // namespace pairs

inline std::string pairs_scene(ByteReader& in) {
  using namespace pairs;
  choose_hostility(in);
  std::string doc = "name = \"fuzz_pairs\"\n";
  if (in.byte() < 64) doc += "gravity = " + vec3(in) + "\n";
  const std::string_view integrator = in.pick(kIntegrators);
  doc += "[simulation]\nintegrator = " + std::string(integrator) + "\n";
  doc += "dt = " + number(in, in.pick(kSteps)) + "\nduration = 0.5\n";
  if (integrator == "\"rk4_adaptive\"" || integrator == "\"sdirk2\"" ||
      integrator == "\"sdirk4\"") {
    doc += "tolerance = " + number(in, "1e-6") + "\n";
  }

  // Bodies: a few, or (one input in eight) up to 100 for the counts.
  const std::uint8_t many = in.byte();
  // (4950 pairs of 100 bodies load in 0.3 s in Release but take over 10 s a step or two
  // instrumented on a loaded machine: the fuzzer stops at 64 bodies, 2016 pairs.)
  const std::size_t n = many < 224 ? 2 + in.byte() % 6 : 2 + in.size(62);
  std::string positions;  // the previous body's position, for coincident and nested bodies
  for (std::size_t i = 0; i < n; ++i) {
    const std::string name = named("b", i);
    // A shape a pair contact refuses (cylinder, point mass, none) only when hostile.
    const std::uint8_t kind = in.byte();
    const char shape = in.byte() >= hostile_from() ? "cpn"[kind % 3]
                       : kind < 100                ? 's'
                       : kind < 130                ? 'h'
                                                   : 'b';
    doc += "[bodies." + name + "]\n";
    doc += std::string("type = ") + (shape == 'p' ? "\"point_mass\"" : "\"rigid_body\"") + "\n";
    doc += "mass = " + number(in, "1.0") + "\n";
    switch (shape) {
      case 's':
        doc += "shape = \"sphere\"\nradius = " + number(in, "0.05") + "\n";
        break;
      case 'h':
        doc += "shape = \"hollow_sphere\"\nradius = " + number(in, "0.1") + "\n";
        break;
      case 'b':
        doc += "shape = \"box\"\nsize = [" + number(in, "0.1") + ", " + number(in, "0.2") + ", " +
               number(in, "0.05") + "]\n";
        break;
      case 'c':
        doc += "shape = \"cylinder\"\nradius = 0.05\nlength = 0.1\n";
        break;
      case 'n':
        doc += "inertia = [0.01, 0.01, 0.01]\n";
        break;
      default:
        break;
    }
    // Where: on the grid, on the previous body's centre (coincident), or just beside it
    // (nested: one inside the other).
    const std::uint8_t where = in.byte();
    std::string position;
    if (where < 170 || positions.empty()) {
      position = vec3(in);
    } else if (where < 210) {
      position = positions;
    } else {  // a nanometre off the grid: inside a body there if one is
      position = "[" + coordinate(in) + ", 1e-9, " + coordinate(in) + "]";
    }
    positions = position.front() == '[' ? position : std::string("[0.0, 0.0, 0.0]");
    doc += "position = " + position + "\n";
    if (shape != 'p' && in.byte() < 128) {
      doc += "orientation = " + std::string(pick(in, kOrientations, kOddOrientations)) + "\n";
    }
    if (in.byte() < 128) doc += "velocity = " + vec3(in) + "\n";
    if (shape != 'p' && in.byte() < 64) doc += "angular_velocity = " + vec3(in) + "\n";
  }

  // Pair contacts.
  std::size_t contact = 0;
  const auto pair = [&](const std::string& a, const std::string& b) {
    doc += "[impedances." + named("c", contact++) + "]\ntype = \"kikuuwe_contact\"\n";
    doc += "body = \"" + a + "\"\nother = \"" + b + "\"\n";
    doc += "stiffness = " + number(in, "1e5") + "\n";
    doc += "damping = " + number(in, "10.0") + "\n";
    doc += "mu = " + number(in, "0.3") + "\n";
    const std::uint8_t extra = in.byte();
    if (extra & 1) doc += "mu_static = " + number(in, "0.4") + "\n";
    if (extra & 2) doc += "stribeck_velocity = " + number(in, "0.01") + "\n";
    if (extra & 4) doc += "viscous = " + number(in, "0.5") + "\n";
    if (extra & 8) doc += "tangential_stiffness = " + number(in, "1e4") + "\n";
    if (extra & 16) doc += "tangential_damping = " + number(in, "1.0") + "\n";
    if (extra & 32) doc += "stick_threshold = " + number(in, "1e-3") + "\n";
    if (extra & 64 && in.byte() >= hostile_from()) {
      doc += "normal = [0.0, 0.0, 1.0]\n";  // a plane's key: refused
    }
  };
  const auto name = [](std::size_t i) { return named("b", i); };
  const std::uint8_t mode = in.byte();
  if (mode < 48 || many >= 224) {  // every two bodies
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) pair(name(i), name(j));
    }
  } else {
    const std::size_t pairs = 1 + in.byte() % 8;
    for (std::size_t k = 0; k < pairs; ++k) {
      const std::uint8_t a = in.byte(), b = in.byte();
      const bool hostile = in.byte() >= hostile_from();
      // Another body; when hostile, maybe itself or one that does not exist (refused).
      const std::size_t j = !hostile && a % n == b % n ? (b + 1) % n : b % n;
      pair(name(a % n), hostile && b >= 192 ? std::string("nobody") : name(j));
    }
  }
  // Floors under some bodies.
  const std::uint8_t floors = in.byte();
  for (std::size_t i = 0; i < n && i < 8; ++i) {
    if ((floors >> i) & 1) {
      doc += "[impedances." + named("floor", i) + "]\ntype = \"kikuuwe_contact\"\nbody = \"" +
             name(i) + "\"\noffset = -0.3\nstiffness = " + number(in, "1e5") + "\ndamping = 10.0\n";
    }
  }
  return doc;
}

}  // namespace stiction::fuzz
