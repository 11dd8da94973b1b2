#include "core/implicit_euler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace stiction::core {

std::vector<bool> implicitly_solved_slots(const Network& network) {
  std::vector<bool> solved(static_cast<std::size_t>(network.state_dim()), true);
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    if (network.capabilities(i).friction == nullptr) continue;
    const Slot s = network.impedance_slot(i);
    for (int k = 0; k < s.state_size; ++k) {
      solved[static_cast<std::size_t>(s.state_offset + k)] = false;
    }
  }
  return solved;
}

ImplicitEulerStepper::ImplicitEulerStepper(int state_dim, double dt)
    : dt_(dt),
      start_(state_dim),
      iterate_(state_dim),
      eval_(state_dim),
      f_(state_dim),
      probe_(state_dim),
      f_probe_(state_dim),
      last_eval_(state_dim) {}

void ImplicitEulerStepper::prepare(Network& network) {
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    const Capabilities& c = network.capabilities(i);
    if (c.friction != nullptr && c.slip != nullptr) friction_elements_.push_back(i);
  }
  const std::vector<bool> solved = implicitly_solved_slots(network);
  for (int i = 0; i < static_cast<int>(solved.size()); ++i) {
    if (solved[static_cast<std::size_t>(i)]) solved_.push_back(i);
  }
  const auto n = static_cast<Eigen::Index>(solved_.size());
  residual_ = Vec::Zero(n);
  delta_ = Vec::Zero(n);
  probe_delta_ = Vec::Zero(n);
  groups_ = coupled_groups(network, solved_);
  for (const auto& g : groups_) {
    const auto m = static_cast<Eigen::Index>(g.size());
    blocks_.push_back(Eigen::MatrixXd::Identity(m, m));
    block_lus_.emplace_back(m);
    block_rhs_.push_back(Vec::Zero(m));
  }
  prepared_ = true;
}

std::vector<std::vector<int>> ImplicitEulerStepper::coupled_groups(const Network& network,
                                                                   const std::vector<int>& solved) {
  // Union-find over the state entries: a body's entries belong together, and an element
  // joins the bodies its map moves and its own state.
  std::vector<int> parent(static_cast<std::size_t>(network.state_dim()));
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  const auto root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      i = parent[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    }
    return i;
  };
  const auto join = [&](int a, int b) { parent[static_cast<std::size_t>(root(a))] = root(b); };
  const auto join_slot = [&](const Slot& s, int anchor) {
    for (int k = 0; k < s.state_size; ++k) join(s.state_offset + k, anchor);
  };
  const auto& admittances = network.admittances();
  for (int j = 0; j < static_cast<int>(admittances.size()); ++j) {
    const Slot s = network.admittance_slot(j);
    if (s.state_size > 0) join_slot(s, s.state_offset);
  }
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    int anchor = -1;
    for (const Admittance* moved : network.map_of(i).admittances()) {
      for (int j = 0; j < static_cast<int>(admittances.size()); ++j) {
        const Slot s = network.admittance_slot(j);
        if (admittances[static_cast<std::size_t>(j)].get() != moved || s.state_size == 0) continue;
        if (anchor < 0) anchor = s.state_offset;
        join(s.state_offset, anchor);
      }
    }
    const Slot own = network.impedance_slot(i);
    if (own.state_size > 0) join_slot(own, anchor >= 0 ? anchor : own.state_offset);
  }
  // Groups of positions in `solved` (the order of the unknowns), in order of first entry.
  std::vector<std::vector<int>> groups;
  std::vector<int> group_of_root(parent.size(), -1);
  for (int r = 0; r < static_cast<int>(solved.size()); ++r) {
    const auto top = static_cast<std::size_t>(root(solved[static_cast<std::size_t>(r)]));
    if (group_of_root[top] < 0) {
      group_of_root[top] = static_cast<int>(groups.size());
      groups.emplace_back();
    }
    groups[static_cast<std::size_t>(group_of_root[top])].push_back(r);
  }
  return groups;
}

void ImplicitEulerStepper::solve_linear() {
  if (groups_.size() == 1) {  // one coupled system: its unknowns in their own order
    delta_.noalias() = block_lus_[0].solve(residual_);
    return;
  }
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    Vec& part = block_rhs_[g];
    part = residual_(groups_[g]);
    part = block_lus_[g].solve(part);
    delta_(groups_[g]) = part;
  }
}

double ImplicitEulerStepper::advance(Network& network, double t, double limit, Vec& x) {
  if (!prepared_) prepare(network);
  const double h = std::min(dt_, limit);
  if (solve(network, t, h, x) || split(network, t, h, x, 1)) return h;
  std::ostringstream message;
  message << "implicit: Newton's iteration did not converge in a step of " << h << " s at t = "
          << t << " s, nor in steps " << (1 << kMaxSplits)
          << " times shorter (a stiff element switching faster than the step can follow, "
             "or a state that is running away)";
  throw std::runtime_error(message.str());
}

void ImplicitEulerStepper::merge(const Vec& iterate, const Vec& start) {
  eval_ = start;
  for (int i : solved_) eval_[i] = iterate[i];
}

double ImplicitEulerStepper::scaled_norm(const Vec& correction, const Vec& x) const {
  double norm = 0.0;
  for (Eigen::Index r = 0; r < correction.size(); ++r) {
    const double scale = kRelative * std::abs(x[solved_[static_cast<std::size_t>(r)]]) + kAbsolute;
    norm = std::max(norm, std::abs(correction[r]) / scale);
  }
  return std::isfinite(norm) ? norm : std::numeric_limits<double>::infinity();
}

void ImplicitEulerStepper::refresh_matrix(Network& network, double t_eval, double h) {
  // Entries of different groups never share a row (coupled_groups), so one evaluation
  // perturbs the k-th entry of every group at once and each group reads its own rows
  // (Curtis, Powell and Reid): as many evaluations as the largest group has entries.
  std::size_t widest = 0;
  for (const auto& g : groups_) widest = std::max(widest, g.size());
  for (auto& block : blocks_) block.setIdentity();
  for (std::size_t k = 0; k < widest; ++k) {
    probe_ = eval_;
    for (const auto& g : groups_) {
      if (k >= g.size()) continue;
      const int j = solved_[static_cast<std::size_t>(g[k])];
      // About sqrt(eps) relative, taken as the difference actually stored, so that the
      // quotient divides by the step the state really made.
      probe_[j] += 1.5e-8 * std::max(std::abs(eval_[j]), 1e-3);
      probe_delta_[g[k]] = probe_[j] - eval_[j];
    }
    network.derivative(t_eval, probe_, h, f_probe_);
    ++evaluations_;
    for (std::size_t gi = 0; gi < groups_.size(); ++gi) {
      const auto& g = groups_[gi];
      if (k >= g.size()) continue;
      const double delta = probe_delta_[g[k]];
      for (std::size_t r = 0; r < g.size(); ++r) {
        const int i = solved_[static_cast<std::size_t>(g[r])];
        blocks_[gi](static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) -=
            h * (f_probe_[i] - f_[i]) / delta;
      }
    }
  }
  for (std::size_t g = 0; g < groups_.size(); ++g) block_lus_[g].compute(blocks_[g]);
  lu_valid_ = true;
  lu_h_ = h;
}

void ImplicitEulerStepper::evaluate_iterate(Network& network, double t_end, double h) {
  merge(iterate_, start_);
  network.derivative(t_end, eval_, h, f_);
  ++evaluations_;
  for (Eigen::Index r = 0; r < residual_.size(); ++r) {
    const int i = solved_[static_cast<std::size_t>(r)];
    residual_[r] = iterate_[i] - start_[i] - h * f_[i];
  }
}

bool ImplicitEulerStepper::move_into_stuck_band(Network& network, double h) {
  // Along the last Newton step (from last_eval_ to eval_), the first point where a sliding
  // element's slip, reversed at the step's end, reaches the middle of its stuck band.
  double alpha = 1.0;
  for (int i : friction_elements_) {
    const Capabilities& c = network.capabilities(i);
    const Slot s = network.impedance_slot(i);
    const auto y = start_.segment(s.state_offset, s.state_size);
    const ConstVecRef before = network.impedance_input(i, last_eval_);
    if (c.friction->regime(before, y, h) != 2) continue;
    const Vec3 s0 = c.slip->slip_velocity(before);
    const Vec3 target = c.friction->unloaded_slip(before, y, h);
    const Vec3 s1 = network.slip_velocity(i, eval_);
    const Vec3 d = s1 - s0;
    if (s0.dot(s1) >= 0.0 || !(d.squaredNorm() > 0.0)) continue;
    alpha = std::min(alpha, std::clamp((target - s0).dot(d) / d.squaredNorm(), 0.0, 1.0));
  }
  if (!(alpha < 1.0)) return false;
  for (int i : solved_) iterate_[i] = last_eval_[i] + alpha * (iterate_[i] - last_eval_[i]);
  return true;
}

bool ImplicitEulerStepper::solve(Network& network, double t, double h, Vec& x) {
  const double t_end = t + h;
  start_ = x;
  eval_ = x;
  // F at the step's start: the first Newton residual, and (for the run loop) the evaluation
  // that reads the state's own slips.
  network.derivative(t_end, x, h, f_);
  ++evaluations_;
  if (keep_start_slope_) f_start_ = f_;
  const auto n = static_cast<Eigen::Index>(solved_.size());
  for (Eigen::Index r = 0; r < n; ++r) residual_[r] = -h * f_[solved_[static_cast<std::size_t>(r)]];
  int formed = 0;  // matrices formed during this step
  if (!lu_valid_ || lu_h_ != h) {
    refresh_matrix(network, t_end, h);
    ++formed;
  }
  iterate_ = x;
  solve_linear();
  double previous = scaled_norm(delta_, start_);
  int moves = 0, halvings = 0;
  for (int k = 0; k < kMaxIterations; ++k) {
    last_eval_ = eval_;
    for (Eigen::Index r = 0; r < n; ++r) iterate_[solved_[static_cast<std::size_t>(r)]] -= delta_[r];
    evaluate_iterate(network, t_end, h);
    // Converged when the next Newton correction is below the tolerance: measured on the
    // correction, not the residual, since a stiff element's residual carries its stiffness
    // times the rounding of the position (K = 1e7 N/m turns 3e-17 m into 1e-9 m/s^2).
    solve_linear();
    double norm = scaled_norm(delta_, start_);
    if (norm > 0.1 * previous && norm > 1.0 && std::isfinite(norm)) {
      // Slow contraction. Either the step crossed a friction element's stuck band (Newton
      // from the sliding side overshoots it, from the other side back: a cycle around the
      // kinks of the clamp), so the iterate goes to the band's middle first; or the matrix
      // is from another regime (an element stuck, sliding, touching or lifting off since)
      // or stale (a contact that a step opens or closes: the iteration cycles between the
      // two sides of its kink with a matrix from either). Either way the matrix is formed
      // anew at the iterate.
      bool moved = moves < kMaxBandMoves && move_into_stuck_band(network, h);
      if (moved) {
        ++moves;
      } else if (norm > previous && halvings < kMaxHalvings) {
        // Growing: the step jumped across kinks the band move does not know (several
        // corners of a tumbling box at once). Half of it, to break the cycle.
        for (int i : solved_) iterate_[i] = 0.5 * (last_eval_[i] + iterate_[i]);
        ++halvings;
        moved = true;
      }
      if (moved) evaluate_iterate(network, t_end, h);
      if (moved || formed < kMaxMatricesPerStep) {
        refresh_matrix(network, t_end, h);
        ++formed;
        solve_linear();
        norm = scaled_norm(delta_, start_);
      }
    }
    // A correction that no longer shrinks, within kRoundingFloor tolerances, is rounding:
    // an entry coupled to stiff springs (a tumbling box's angular velocity) jitters by a few
    // 1e-13 from one iterate to the next however exact the matrix.
    const bool at_floor = norm <= kRoundingFloor && norm > 0.5 * previous;
    if (norm <= 1.0 || at_floor) {
      // Every entry moves by h times F at the solution: the positions by the new velocities
      // and a stuck friction state by the slip velocity there, alike (no drift).
      x = start_ + h * f_;
      network.project(x);
      return true;
    }
    if (!std::isfinite(norm)) return false;
    previous = norm;
  }
  return false;
}

bool ImplicitEulerStepper::apply_inverse(Vec& v) {
  if (!lu_valid_) return false;
  for (Eigen::Index r = 0; r < residual_.size(); ++r) residual_[r] = v[solved_[static_cast<std::size_t>(r)]];
  solve_linear();
  for (Eigen::Index r = 0; r < delta_.size(); ++r) v[solved_[static_cast<std::size_t>(r)]] = delta_[r];
  return true;
}

bool ImplicitEulerStepper::split(Network& network, double t, double h, Vec& x, int depth) {
  if (depth > kMaxSplits) return false;
  const double half = 0.5 * h;
  for (int part = 0; part < 2; ++part) {
    const double at = t + part * half;
    if (!solve(network, at, half, x) && !split(network, at, half, x, depth + 1)) return false;
  }
  return true;
}

}  // namespace stiction::core
