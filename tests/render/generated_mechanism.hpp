// Generated scenes for the mechanism's tests: bodies at random places and orientations with
// springs, dampers and force and torque sources between random anchors, and a hand-written
// trajectory (constant velocities, sources ramping from zero to their peak at the end).
#pragma once

#include <random>
#include <string>
#include <vector>

#include "core/trajectory.hpp"
#include "core/types.hpp"

namespace stiction::render::testing {

inline std::string vec(const core::Vec3& v) {
  std::string s = "[";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "[" + string
  s += std::to_string(v.x());
  s += ", ";
  s += std::to_string(v.y());
  s += ", ";
  s += std::to_string(v.z());
  s += "]";
  return s;
}

inline core::Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  core::Vec3 v(g(rng), g(rng), g(rng));
  return v.norm() > 1e-6 ? core::Vec3(v.normalized()) : core::Vec3::UnitX();
}

// Bodies 0..n-1 (point masses, spheres, boxes) at random places and random fixed
// orientations, moving at constant random velocities; springs from random points of them to
// the world or to another body; force sources (world or body frame) and torque sources with
// values along a random direction growing from 0 (a ramp), so each has its peak at the end.
struct Generated {
  std::string toml;
  core::Trajectory trajectory{std::vector<std::string>{"t"}};
};

inline Generated generated_mechanism(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 2 + static_cast<int>(rng() % 3);
  std::string toml = "name = \"generated\"\ngravity = [0.0, 0.0, 0.0]\n";
  std::vector<std::string> columns{"t"};
  struct Body {
    std::string name, kind;
    core::Vec3 p0, v;
    core::Quat q;
  };
  std::vector<Body> bodies;
  for (int i = 0; i < n; ++i) {
    Body b{"body_" + std::to_string(i),
           std::vector<std::string>{"point_mass", "sphere", "box"}[rng() % 3],
           core::Vec3(2.0 * u(rng), 2.0 * u(rng), 0.5 + u(rng)), 0.3 * random_unit(rng),
           core::Quat(Eigen::AngleAxisd(3.0 * u(rng), random_unit(rng)))};
    toml += "[bodies." + b.name + "]\n";
    if (b.kind == "point_mass") {
      toml += "type = \"point_mass\"\nmass = 1.0\n";
      b.q = core::Quat::Identity();
    } else if (b.kind == "sphere") {
      toml += "type = \"rigid_body\"\nshape = \"sphere\"\nmass = 1.0\nradius = " +
              std::to_string(0.05 + 0.1 * (u(rng) + 1.0)) + "\n";
    } else {
      toml += "type = \"rigid_body\"\nshape = \"box\"\nmass = 1.0\nsize = " +
              vec(core::Vec3(0.1 + 0.1 * (u(rng) + 1.0), 0.1, 0.05 + 0.1 * (u(rng) + 1.0))) + "\n";
    }
    toml += "position = " + vec(b.p0) + "\n";
    for (const char* a : {"x", "y", "z"}) columns.push_back(b.name + ".p." + a);
    if (b.kind != "point_mass") {
      for (const char* a : {"w", "x", "y", "z"}) columns.push_back(b.name + ".q." + a);
    }
    bodies.push_back(b);
  }
  const int springs = 1 + static_cast<int>(rng() % 3);
  for (int k = 0; k < springs; ++k) {
    const int a = static_cast<int>(rng() % n);
    const int other = static_cast<int>(rng() % (n + 1)) - 1;  // -1: the world
    toml += "[impedances.spring_" + std::to_string(k) + "]\ntype = \"spring_damper\"\nbody = \"" +
            bodies[a].name + "\"\npoint = " + vec(0.05 * random_unit(rng)) +
            "\nstiffness = 10.0\n" + "damping = " + std::to_string(rng() % 2 ? 1.0 : 0.0) + "\n";
    if (other >= 0 && other != a) toml += "other = \"" + bodies[other].name + "\"\n";
    toml += "other_point = " + vec(core::Vec3(2.0 * u(rng), 2.0 * u(rng), 0.5 + u(rng))) + "\n";
    if (k == 1) toml += "length = 0.3\n";
  }
  struct Load {
    std::string name;
    bool torque;
    core::Vec3 direction;
  };
  std::vector<Load> loads;
  for (int k = 0; k < 2; ++k) {
    const int a = static_cast<int>(rng() % n);
    const bool torque = k == 1 && bodies[a].kind != "point_mass";
    Load l{"load_" + std::to_string(k), torque, random_unit(rng)};
    if (torque) l.direction = core::Vec3::UnitX() * (rng() % 2 ? 1.0 : -1.0);
    toml += "[impedances." + l.name + "]\nbody = \"" + bodies[a].name + "\"\n";
    if (torque) {
      toml += "type = \"torque_source\"\naxis = " + vec(random_unit(rng)) + "\ntorque = 1.0\n";
      columns.push_back(l.name + ".tau");
    } else {
      toml += "type = \"force_source\"\npoint = " + vec(0.05 * random_unit(rng)) + "\nframe = \"" +
              std::string(rng() % 2 ? "body" : "world") + "\"\nforce = [1.0, 0.0, 0.0]\n";
      for (const char* ax : {"x", "y", "z"}) columns.push_back(l.name + ".f." + ax);
    }
    loads.push_back(l);
  }
  Generated g;
  g.toml = toml;
  g.trajectory = core::Trajectory(columns);
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.02 * i;
    std::vector<double> row{t};
    for (const Body& b : bodies) {
      const core::Vec3 p = b.p0 + t * b.v;
      row.insert(row.end(), {p.x(), p.y(), p.z()});
      if (b.kind != "point_mass") row.insert(row.end(), {b.q.w(), b.q.x(), b.q.y(), b.q.z()});
    }
    for (const Load& l : loads) {
      const double value = 3.0 * t;  // the peak at the end, 6
      if (l.torque) {
        row.push_back(value * l.direction.x());
      } else {
        const core::Vec3 f = value * l.direction;
        row.insert(row.end(), {f.x(), f.y(), f.z()});
      }
    }
    g.trajectory.append(row.data());
  }
  return g;
}

}  // namespace stiction::render::testing
