// One engine at one setting (integrator, step) behind the interface bench_peers drives: set
// up a problem at rest, step, read the body. Set-up and reading are not timed; step() is.
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
  // Builds the problem's world at rest at t = 0 (discarding any previous one).
  virtual void reset(Problem problem) = 0;
  // One step of dt().
  virtual void step() = 0;
  // The body's centre position, velocity and angular velocity, world frame.
  virtual void read(Sample& sample) const = 0;
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

}  // namespace stiction::peers
