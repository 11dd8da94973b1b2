// Ratios printed by bench_step (issue 13): the run loop against the bare step, and the
// planar arm's cost exponent. Times are the thread's CPU time, the least of a few repeats
// (other processes only add time), and the figures are ratios measured in one process; the
// loop ratios also as the median of the per-repeat ratios.
#pragma once

namespace stiction::bench {

// core::simulate on sphere_roll (1 kHz output) and on 100 spheres against the same number
// of bare RungeKuttaStepper::step calls; prints both ratios (rows in memory, and streamed
// to a sink as `run` does).
void print_loop_ratios();

// ns per PlanarArm::derivative at n = 8, 16, 32, 64 for the O(n) articulated-body method and
// for the mass-matrix method it replaced; prints both and the least-squares exponent.
void print_arm_exponents();

}  // namespace stiction::bench
