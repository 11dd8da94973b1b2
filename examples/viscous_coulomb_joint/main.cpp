// A network built in C++ against the installed library: a one-link planar arm (stiction's
// planar_arm admittance) driven by a motor torque T0 for 2 s and then released, through the
// custom viscous-plus-Coulomb joint above. Simulated with stiction's RK4 and written with
// its CSV writer. Checked against the closed forms:
//   driven:   J omega' = T0 - F - b omega  ->  omega(2 s) = w_inf (1 - exp(-2 b / J)),
//             w_inf = (T0 - F) / b;
//   released: J omega' = -F - b omega      ->  omega = (F/b + omega(2)) exp(-(t - 2) b / J) - F/b,
//             reaching 0 at 2 s + (J / b) ln(1 + b omega(2) / F), and then staying put (the
//             Coulomb part holds it without drift).
// Usage: viscous_coulomb_joint [OUT.csv]   (exit 0 when the run matches the closed forms)
#include <cmath>
#include <cstdio>
#include <memory>

#include <stiction/components/admittance/planar_arm.hpp>
#include <stiction/components/impedance/torque_source.hpp>
#include <stiction/components/maps/joint_map.hpp>
#include <stiction/core/network.hpp>
#include <stiction/core/simulation.hpp>
#include <stiction/io/csv_writer.hpp>

#include "viscous_coulomb_joint.hpp"

using namespace stiction;

int main(int argc, char** argv) {
  const double T0 = 1.5, released_at = 2.0;
  example::ViscousCoulombParams joint;
  joint.viscous = 0.02;  // a time constant J / b of 0.13 s

  core::Network network;
  components::PlanarArmParams arm_params;
  arm_params.links.push_back(components::box_link(0.2, 0.02, 0.2));
  auto arm = std::make_unique<components::PlanarArm>("arm", arm_params);
  const components::PlanarArm& arm_ref = *arm;
  network.add_admittance(std::move(arm));
  network.add_impedance(
      std::make_unique<components::TorqueSource>(
          "motor", std::vector<components::TorqueSource::Profile>{
                       [=](double t) { return t < released_at ? T0 : 0.0; }}),
      std::make_unique<components::JointMap>(arm_ref, 0));
  network.add_impedance(std::make_unique<example::ViscousCoulombJoint>("joint", joint),
                        std::make_unique<components::JointMap>(arm_ref, 0));
  network.finalize();

  core::RunOptions options;
  options.integrator = "rk4";
  options.dt = 1e-4;
  options.duration = 4.0;
  options.output_rate = 1000.0;
  const core::RunResult result = core::simulate(network, options);
  if (result.instability) {
    std::fprintf(stderr, "unstable at t = %g s: %s\n", result.instability->time, result.instability->reason.c_str());
    return 1;
  }
  const char* out = argc > 1 ? argv[1] : "viscous_coulomb_joint.csv";
  io::write_csv(result.trajectory, out);

  // Closed forms (J about the joint: the box link's inertia about its end). The torque step
  // at t = 2 s falls on a step boundary that RK4's last stage already sees, so the driven
  // phase is compared one row before it.
  const auto& link = arm_ref.params().links[0];
  const double J = link.inertia + link.mass * link.com * link.com;
  const double b = joint.viscous, F = joint.coulomb, time_constant = J / b;
  const double t_before = released_at - 1.0 / options.output_rate;
  const double w_before = (T0 - F) / b * (1.0 - std::exp(-t_before / time_constant));
  const double w_release = (T0 - F) / b * (1.0 - std::exp(-released_at / time_constant));
  // Released, omega = (F/b + w_release) exp(-(t - 2) / (J/b)) - F/b until it reaches 0.
  const auto time_at = [&](double w) {
    return released_at + time_constant * std::log((F / b + w_release) / (F / b + w));
  };
  const core::Trajectory& tr = result.trajectory;
  const auto column = [&](const char* name) {
    for (int c = 0; c < tr.column_count(); ++c) {
      if (tr.columns()[c] == name) return c;
    }
    return -1;
  };
  const int omega = column("arm.omega.0"), theta = column("arm.theta.0");
  if (omega < 0 || theta < 0) {
    std::fprintf(stderr, "no arm.omega.0 / arm.theta.0 column\n");
    return 1;
  }
  const int before_row = static_cast<int>(std::lround(t_before * options.output_rate));
  // When the slide has shed 99% of its speed (the last 1% ends in the friction spring's
  // brief ringing, which the ideal Coulomb law does not have).
  double t_slowed = -1.0;
  for (int r = before_row; r < tr.row_count(); ++r) {
    if (tr.at(r, omega) < 0.01 * w_release) {
      // Interpolated between the two rows around the crossing.
      const double w0 = tr.at(r - 1, omega), w1 = tr.at(r, omega), target = 0.01 * w_release;
      t_slowed = tr.at(r - 1, 0) + (w0 - target) / (w0 - w1) * (tr.at(r, 0) - tr.at(r - 1, 0));
      break;
    }
  }
  const int last = tr.row_count() - 1;
  const int half_second = static_cast<int>(0.5 * options.output_rate);
  const double drift = std::abs(tr.at(last, theta) - tr.at(last - half_second, theta));
  std::printf("omega at t = %.3f s: %.9f rad/s (closed form %.9f)\n", t_before, tr.at(before_row, omega), w_before);
  std::printf("down to 1%% of its speed at %.4f s (closed form %.4f); stops for good at %.4f s\n", t_slowed,
              time_at(0.01 * w_release), time_at(0.0));
  std::printf("after the stop: omega %.3g rad/s, drift over the last 0.5 s %.3g rad\nwrote %s (%d rows)\n",
              tr.at(last, omega), drift, out, tr.row_count());
  const bool ok = std::abs(tr.at(before_row, omega) - w_before) < 1e-6 * w_before &&
                  std::abs(t_slowed - time_at(0.01 * w_release)) < 1e-3 && std::abs(tr.at(last, omega)) < 1e-9 &&
                  drift < 1e-9;
  std::printf("%s\n", ok ? "matches the closed forms" : "DOES NOT match the closed forms");
  return ok ? 0 : 1;
}
