// One engine at one setting (integrator, step) behind the interface bench_peers drives: set
// up a problem at rest, step, read the bodies. Set-up is not timed; step() and the reading
// bench_peers does after every step (or every sample interval) are.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "problems.hpp"

namespace stiction::peers {

class Peer {
 public:
  virtual ~Peer() = default;
  virtual std::string engine() const = 0;
  virtual std::string settings() const = 0;
  virtual double dt() const = 0;
  // Whether this engine at this setting can express the problem (no row where it cannot).
  virtual bool expresses(Problem /*problem*/) const { return true; }
  // Whether this setting is one of the rows of the hold benchmark (ramp_grid, pinch): a
  // choice of the rows shown, not an inability (stiction keeps rk4 1e-4 s and implicit
  // 1/60 s, Bullet its rows with sleeping off).
  virtual bool in_hold_benchmark() const { return true; }
  // Builds the case's world at rest at t = 0 (discarding any previous one).
  virtual void reset(const Case& c) = 0;
  // One step of dt().
  virtual void step() = 0;
  // Body i's centre position, velocity and angular velocity, world frame: i < c.count, the
  // spheres in the order of spheres_v0(i, n); the pendulum's bar is body 0; the pinch's
  // block is body 0, its fingers 1 (at -x) and 2 (at +x).
  virtual void read(int body, Sample& sample) const = 0;
};

using Peers = std::vector<std::unique_ptr<Peer>>;

// A sample from the body's position, velocity and world angular velocity, each anything
// indexable 0..2 (every engine has its own vector type).
template <typename P, typename V, typename W>
void fill_sample(Sample& s, const P& p, const V& v, const W& w) {
  for (int i = 0; i < 3; ++i) {
    s.p[i] = p[i];
    s.v[i] = v[i];
    s.w[i] = w[i];
  }
}

// Each adapter adds its settings' rows (an engine not built in adds none). The stiction
// adapter prints a line and adds no row for an integrator this build does not have.
void add_stiction_peers(Peers& peers);
void add_ode_peers(Peers& peers);
void add_bullet_peers(Peers& peers);
void add_mujoco_peers(Peers& peers);
void add_dart_peers(Peers& peers);
void add_siconos_peers(Peers& peers);

}  // namespace stiction::peers
