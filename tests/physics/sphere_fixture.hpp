// Simulation I built directly from components (no scene file), so that the closed-form
// tests can vary mass, radius, friction and inertia freely.
#pragma once

#include <memory>
#include <random>
#include <string>

#include "components/admittance/rigid_body.hpp"
#include "components/impedance/kikuuwe_contact.hpp"
#include "components/maps/contact_point_map.hpp"
#include "core/events.hpp"
#include "core/network.hpp"
#include "core/simulation.hpp"
#include "core/trajectory.hpp"
#include "trajectory_rows.hpp"

namespace stiction::testing {

struct SphereCase {
  double mass = 0.3;
  double radius = 0.2;
  double inertia_factor = 0.4;  // J = factor M R^2: 2/5 solid, 2/3 hollow
  double stiffness = 1e7;
  double damping = 10.0;
  double mu = 0.1;
  double v0 = 2.0;
  double g = 9.8;
  double height = 1.01 * 0.2;  // initial centre height
};

inline std::unique_ptr<core::Network> make_sphere(const SphereCase& c) {
  using namespace components;
  auto net = std::make_unique<core::Network>();
  RigidBodyParams body;
  body.mass = c.mass;
  body.inertia = core::Mat3::Identity() * (c.inertia_factor * c.mass * c.radius * c.radius);
  body.position = core::Vec3(0, 0, c.height);
  body.velocity = core::Vec3(c.v0, 0, 0);
  body.gravity = core::Vec3(0, 0, -c.g);
  auto sphere = std::make_unique<RigidBody>("sphere", body);
  const auto& sphere_ref = *sphere;
  net->add_admittance(std::move(sphere));
  KikuuweContactParams contact;
  contact.stiffness = c.stiffness;
  contact.damping = c.damping;
  contact.mu = c.mu;
  net->add_impedance(std::make_unique<KikuuweContact>("ground", contact),
                     std::make_unique<ContactPointMap>(sphere_ref, c.radius, contact.normal));
  net->finalize();
  return net;
}

// Height at which the sphere rests on the spring of the contact: no bounce.
inline double resting_height(const SphereCase& c) {
  return c.radius - c.mass * c.g / c.stiffness;
}

// A sphere with generated mass, radius, inertia (solid or hollow), mu and launch speed,
// damped at the paper's ratio, resting at its static deflection.
inline SphereCase random_sphere(std::mt19937& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); };
  SphereCase c;
  c.mass = uniform(0.1, 5.0);
  c.radius = uniform(0.02, 0.5);
  c.inertia_factor = uniform(0.0, 1.0) < 0.5 ? 0.4 : 2.0 / 3.0;
  c.mu = uniform(0.05, 0.8);
  c.v0 = uniform(0.5, 4.0);
  c.damping = 10.0 * c.mass / 0.3;  // the paper's damping ratio
  c.height = resting_height(c);
  return c;
}


inline double first_stick_time(const core::RunResult& result) {
  for (const auto& h : result.slip_events) {
    if (h.component == "ground") return h.monitor.stick_time();
  }
  return -1.0;
}

}  // namespace stiction::testing
