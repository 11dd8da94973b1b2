// What the step analysis of a scene depends on besides its regimes, as numbers: every stiff
// element's stiffness and damping (core::StiffnessHint) and the mobility it sees (the inverse
// of the effective mass or inertia it pushes at the initial state), every body's response to
// a unit input (its inverse mass or inertia), with the integrator and the pilot's step and
// span. Two scenes with the same fingerprint have the same linear
// dynamics, so a sweep shares one step analysis among its points whose varied keys leave it
// unchanged (a friction coefficient, a source's law) and says so (issue 35 item 6).
#pragma once

#include <string>
#include <vector>

#include "core/network.hpp"
#include "scene/scene.hpp"

namespace stiction::services {

// Mobility (inverse effective mass or inertia) that impedance i sees at the state x0 (the
// network's initial state), read at the velocity its map names as conjugate to its force
// (CoordinateMap::conjugate_velocity_offset); NaN for a map that names none.
// Only the admittances its push reaches are evaluated; `work`, when given, is increased by
// their state sizes (twice per force axis).
double largest_mobility(core::Network& network, int i, const core::Vec& x0,
                        double* work = nullptr);

// The work (admittance state numbers evaluated) the single-element mobilities may take in
// all, in `check` and in the fingerprint (issue 39: a URDF chain of n joints with <limit>
// pushes its whole tree once per joint, n^2: 38 s at 5000 joints). Beyond it the remaining
// elements' mobilities are NaN ("not computed").
inline constexpr double kMobilityWork = 2e6;

struct DynamicsFingerprint {
  std::string integrator;
  double pilot_dt = 0.0;
  double duration = 0.0;
  int state_dim = 0;
  std::vector<double> numbers;  // per stiff element: stiffness, damping, mobility
  bool operator==(const DynamicsFingerprint& other) const;
};

DynamicsFingerprint dynamics_fingerprint(scene::Scene& scene);

}  // namespace stiction::services
