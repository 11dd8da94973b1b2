#include "core/stability.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "core/energy_budget.hpp"
#include "core/implicit_euler.hpp"
#include "core/integrator.hpp"
#include "core/islands.hpp"
#include "core/spectrum.hpp"

namespace stiction::core {
namespace {

// Runs the scene at its options and calls visit(step, t, x, work) before every step.
template <typename Visit>
void walk_run(Network& network, const RunOptions& options, Visit visit) {
  auto stepper =
      make_stepper(options.integrator, network.state_dim(), options.dt, options.tolerance);
  Vec x = network.initial_state();
  double t = 0.0, work = 0.0;
  const bool sources = network.has_sources();
  double power = sources ? std::abs(network.source_power(0.0, x)) : 0.0;
  for (long k = 0; t < options.duration; ++k) {
    if (options.stop != nullptr && options.stop->load(std::memory_order_relaxed)) break;
    visit(k, t, x, work);
    const double h = stepper->advance(network, t, options.duration - t, x);
    t += h;
    if (!x.allFinite()) break;
    if (sources) {
      const double p = std::abs(network.source_power(t, x));
      work += 0.5 * (power + p) * h;
      power = p;
    }
  }
}

// Groups of state indices that no linearization couples (see coupled_groups).
using Groups = std::vector<std::vector<int>>;

// One island of the network (core/islands.hpp) at a state x, seen as a system of its own:
// its state entries y, and F, F with friction held and the kinematics restricted to them.
// No element couples islands, so the step map of the network is block diagonal over them
// and each is analysed alone, at the cost of its own size: a scene of 1000 separate bodies
// is 1000 small problems, not one of 13000 states. `scratch` and `scratch_out` are whole
// state vectors equal to x outside the island (shared by the islands of one state: each
// writes only its own entries, and puts x back there when it is done).
class IslandSystem {
 public:
  IslandSystem(Network& network, const Island& island, double t, const Vec& x, Vec& scratch,
               Vec& scratch_out)
      : network_(network), island_(island), t_(t), x_(x), full_(scratch), out_(scratch_out) {
    y_.resize(size());
    for (int r = 0; r < size(); ++r) y_[r] = x[entry(r)];
  }
  IslandSystem(const IslandSystem&) = delete;
  IslandSystem& operator=(const IslandSystem&) = delete;
  ~IslandSystem() {
    for (int e : island_.states) full_[e] = x_[e];
  }
  int size() const { return static_cast<int>(island_.states.size()); }
  int entry(int r) const { return island_.states[static_cast<std::size_t>(r)]; }
  const Vec& state() const { return y_; }
  const Vec& whole_state() const { return x_; }
  double t() const { return t_; }
  Network& network() { return network_; }
  const Island& island() const { return island_; }

  void derivative(const Vec& y, double tau, Vec& out) {
    place(y);
    network_.derivative_part(t_, full_.data(), tau, out_.data(), island_);
    take(out);
  }
  // With the clamped friction held at its value at x.
  void derivative_friction_held(const Vec& y, double tau, Vec& out) {
    place(y);
    network_.derivative_friction_held(t_, full_, tau, out_, x_, &island_);
    take(out);
  }
  void kinematics(const Vec& y, Vec& out) {
    place(y);
    network_.kinematics(full_, out_, &island_);
    take(out);
  }

 private:
  void place(const Vec& y) {
    for (int r = 0; r < size(); ++r) full_[entry(r)] = y[r];
  }
  void take(Vec& out) {
    out.resize(size());
    for (int r = 0; r < size(); ++r) out[r] = out_[entry(r)];
  }

  Network& network_;
  const Island& island_;
  double t_;
  const Vec& x_;
  Vec& full_;
  Vec& out_;
  Vec y_;
};

// Whether the forward and backward differences of a column agree: the state is not on a
// switching surface at this perturbation size.
bool one_sided_agree(const Eigen::Ref<const Vec>& forward, const Eigen::Ref<const Vec>& backward) {
  const double scale = 1.0 + forward.lpNorm<Eigen::Infinity>() + backward.lpNorm<Eigen::Infinity>();
  return (forward - backward).lpNorm<Eigen::Infinity>() <= 1e-4 * scale;
}

// Column i of dF/dx at x by central differences into J, from F at x (`center`); false where
// x lies on a switching surface of some element (the one-sided differences disagree at every
// perturbation size tried).
template <typename Function>
bool central_column(const Function& F, const Vec& x, const Vec& center, int i, Eigen::MatrixXd& J) {
  const int n = static_cast<int>(x.size());
  Vec plus(n), minus(n), f_plus(n), f_minus(n);
  // A state near a switching surface (a contact barely closed, friction near its limit)
  // needs a perturbation smaller than its distance to the surface: try finer ones before
  // giving up. Rounding limits the finest to about 1e-5 relative accuracy, enough here.
  for (double relative : {1e-7, 1e-9, 1e-11}) {
    const double delta = relative * std::max(std::abs(x[i]), 1e-3);
    plus = x;
    plus[i] += delta;
    minus = x;
    minus[i] -= delta;
    F(plus, f_plus);
    F(minus, f_minus);
    const Vec forward = (f_plus - center) / delta;
    const Vec backward = (center - f_minus) / delta;
    if (one_sided_agree(forward, backward)) {
      J.col(i) = 0.5 * (forward + backward);
      return true;
    }
  }
  return false;
}

// What the linearizations of an island at a state can couple (state_sparsity): which rows
// each column can move, at any stage size, with friction held or not, and in the kinematics.
struct Sparsity {
  std::vector<std::vector<int>> rows;  // rows[i]: the rows that column i moves
  // Columns no row shares, each color in ascending order: one perturbation moves all of a
  // color and each column reads its own rows (Curtis, Powell and Reid's compression). Bodies
  // that never touch are the coarse case; inside a body, a sliding sphere's 15 columns take
  // 4 to 11 perturbations (mostly 6) instead of 15.
  Groups colors;
  double eigen_work = 0.0;  // the cubes of the pattern's irreducible blocks, summed
};

// dF/dx at x by central differences, F(at, out) any map of the state; empty on a switching
// surface. With `sparsity`, the columns of each color are perturbed at once. A column whose
// compressed differences disagree is redone alone.
template <typename Function>
std::optional<Eigen::MatrixXd> central_jacobian(const Function& F, const Vec& x,
                                                const Sparsity* sparsity = nullptr) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  Vec center(n);
  F(x, center);
  Vec plus(n), minus(n), f_plus(n), f_minus(n);
  std::vector<double> delta(static_cast<std::size_t>(n), 0.0);
  const auto alone = [&](int i) { return central_column(F, x, center, i, J); };
  if (sparsity == nullptr) {
    for (int i = 0; i < n; ++i) {
      if (!alone(i)) return std::nullopt;
    }
    return J;
  }
  Vec forward(n), backward(n);
  for (const std::vector<int>& color : sparsity->colors) {
    plus = x;
    minus = x;
    for (int i : color) {
      const auto k = static_cast<std::size_t>(i);
      delta[k] = 1e-7 * std::max(std::abs(x[i]), 1e-3);
      plus[i] += delta[k];
      minus[i] -= delta[k];
    }
    F(plus, f_plus);
    F(minus, f_minus);
    for (int i : color) {
      const double d = delta[static_cast<std::size_t>(i)];
      const std::vector<int>& rows = sparsity->rows[static_cast<std::size_t>(i)];
      const int m = static_cast<int>(rows.size());
      for (int r = 0; r < m; ++r) {
        const int row = rows[static_cast<std::size_t>(r)];
        forward[r] = (f_plus[row] - center[row]) / d;
        backward[r] = (center[row] - f_minus[row]) / d;
      }
      if (one_sided_agree(forward.head(m), backward.head(m))) {
        for (int r = 0; r < m; ++r) {
          J(rows[static_cast<std::size_t>(r)], i) = 0.5 * (forward[r] + backward[r]);
        }
      } else if (!alone(i)) {
        return std::nullopt;
      }
    }
  }
  return J;
}

// J = dF/dx of the island at its state (tau), with clamping friction held at its value
// there if asked.
std::optional<Eigen::MatrixXd> jacobian(IslandSystem& sys, double tau, bool friction_held,
                                        const Sparsity* sparsity = nullptr) {
  return central_jacobian(
      [&](const Vec& at, Vec& out) {
        if (friction_held) {
          sys.derivative_friction_held(at, tau, out);
        } else {
          sys.derivative(at, tau, out);
        }
      },
      sys.state(), sparsity);
}

// The state's indices in groups that no matrix of `matrices` couples (i and j share a group
// when some matrix has a nonzero (i, j) or (j, i)). Bodies that never touch form groups of
// their own: a step map built from such matrices is block diagonal over the groups, and its
// spectral radius is the largest of the blocks'. Central differences leave the entries of
// an uncoupled pair exactly zero.
Groups coupled_groups(const std::vector<const Eigen::MatrixXd*>& matrices, int n) {
  std::vector<int> parent(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) parent[static_cast<std::size_t>(i)] = i;
  const auto root = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      i = parent[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    }
    return i;
  };
  for (const Eigen::MatrixXd* m : matrices) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        if ((*m)(i, j) != 0.0) parent[static_cast<std::size_t>(root(i))] = root(j);
      }
    }
  }
  std::map<int, std::vector<int>> by_root;
  for (int i = 0; i < n; ++i) by_root[root(i)].push_back(i);
  Groups groups;
  for (auto& [r, members] : by_root) groups.push_back(std::move(members));
  return groups;
}

// How the radii of one island at one state are computed: its sparsity, and the
// linearizations that do not depend on the step, kept across the steps a search tries there.
struct SiteLinearization {
  const Sparsity* sparsity = nullptr;
  // The step search only asks whether a radius exceeds 1 + kUnstableGrowth (unstable_step):
  // a radius at most that may then be any value at most that (a bound on the blocks of the
  // step map, spectral_radius_beyond; implicit_step_radius skips the growth it would be
  // divided by).
  bool verdict_only = false;
  // F's Jacobian at stage size 0 (the first stage of every explicit tableau: the same at
  // every step tried), with and without friction held, once computed (empty inside: on a
  // switching surface), and the kinematics' Jacobian (symplectic Euler's positions).
  std::optional<std::optional<Eigen::MatrixXd>> at_rest[2];
  std::optional<std::optional<Eigen::MatrixXd>> kinematics;
};

// The spectral radius of a step map as the site asks for it.
std::optional<double> step_map_radius(const Eigen::MatrixXd& phi, const SiteLinearization& site) {
  return site.verdict_only ? spectral_radius_beyond(phi, 1.0 + kUnstableGrowth)
                           : spectral_radius(phi);
}

// J at stage size tau, from the site's store when tau is 0.
const std::optional<Eigen::MatrixXd>& stage_jacobian(IslandSystem& sys, double tau,
                                                     bool friction_held, SiteLinearization& site,
                                                     std::optional<Eigen::MatrixXd>& fresh) {
  if (tau == 0.0) {
    auto& kept = site.at_rest[friction_held ? 1 : 0];
    if (!kept) kept = jacobian(sys, tau, friction_held, site.sparsity);
    return *kept;
  }
  fresh = jacobian(sys, tau, friction_held, site.sparsity);
  return fresh;
}

// Spectral radius of the linear step map of a Runge-Kutta tableau, from the Jacobians at its
// stage sizes, built and solved group by group (coupled_groups): sum n_g^3, not n^3.
std::optional<double> rk_step_radius(IslandSystem& sys, const Tableau& tab, double h,
                                     bool friction_held, SiteLinearization& site) {
  const int n = sys.size();
  const int s = tab.stages;
  // One Jacobian per distinct stage size.
  std::map<double, std::optional<Eigen::MatrixXd>> fresh;
  std::map<double, const Eigen::MatrixXd*> by_tau;
  for (int r = 0; r < s; ++r) {
    const double tau = h * tab.d[r];
    if (by_tau.count(tau) != 0) continue;
    const auto& J = stage_jacobian(sys, tau, friction_held, site, fresh[tau]);
    if (!J) return std::nullopt;
    by_tau.emplace(tau, &*J);
  }
  std::vector<const Eigen::MatrixXd*> jacobians;
  for (const auto& [tau, J] : by_tau) jacobians.push_back(J);
  double radius = 0.0;
  for (const std::vector<int>& group : coupled_groups(jacobians, n)) {
    const int m = static_cast<int>(group.size());
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(m, m);
    std::vector<Eigen::MatrixXd> K(static_cast<std::size_t>(s));
    Eigen::MatrixXd phi = I;
    for (int r = 0; r < s; ++r) {
      Eigen::MatrixXd stage = I;
      for (int j = 0; j < r; ++j) {
        if (tab.a[r * s + j] != 0.0) stage += h * tab.a[r * s + j] * K[static_cast<std::size_t>(j)];
      }
      K[static_cast<std::size_t>(r)] = (*by_tau.at(h * tab.d[r]))(group, group) * stage;
      phi += h * tab.b[r] * K[static_cast<std::size_t>(r)];
    }
    const auto r = step_map_radius(phi, site);
    if (!r) return std::nullopt;
    radius = std::max(radius, *r);
  }
  return radius;
}

// Symplectic Euler: x' = x + h F(x; h), then the positions move with the new velocities,
// p(k+1) = p(k) + h G(x'), G the admittances' kinematics. Group by group as above.
std::optional<double> symplectic_step_radius(IslandSystem& sys, double h, bool friction_held,
                                             SiteLinearization& site) {
  const int n = sys.size();
  auto J = jacobian(sys, h, friction_held, site.sparsity);
  if (!J) return std::nullopt;
  // G's Jacobian: the kinematics are smooth (p_dot = v, q_dot = Q(w) q) and do not depend
  // on the step.
  if (!site.kinematics) {
    site.kinematics = central_jacobian([&](const Vec& at, Vec& out) { sys.kinematics(at, out); },
                                       sys.state(), site.sparsity);
  }
  const auto& G = *site.kinematics;
  if (!G) return std::nullopt;
  const auto& positions = sys.network().position_slots();
  double radius = 0.0;
  for (const std::vector<int>& group : coupled_groups({&*J, &*G}, n)) {
    const int m = static_cast<int>(group.size());
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(m, m) + h * (*J)(group, group);
    Eigen::MatrixXd phi = A;
    const Eigen::MatrixXd moved = h * (*G)(group, group) * A;
    for (int i = 0; i < m; ++i) {
      const int entry = sys.entry(group[static_cast<std::size_t>(i)]);
      if (!positions[static_cast<std::size_t>(entry)]) continue;
      phi.row(i) = moved.row(i);
      phi(i, i) += 1.0;
    }
    const auto r = step_map_radius(phi, site);
    if (!r) return std::nullopt;
    radius = std::max(radius, *r);
  }
  return radius;
}

// How much backward Euler itself grows the linearization over a step whose h J is given:
// the largest |1 / (1 - mu)| over the eigenvalues mu of h J with a positive real part, at
// least 1. A state where the linearization grows (a sliding contact about a point of its
// path, a rolling ball's orientation about its orbit: real eigenvalues of a few 1/s) has
// modes that any method amplifies, and backward Euler more than the flow (1 / (1 - z) >
// exp(z)): at 1/60 s a rolling ball's +3.5/s mode is 1.062 a step. That is the method's
// accuracy, never the clamped friction states' explicit part, so the implicit step's radius
// is taken relative to backward Euler's own on the same linearization; measured against the
// flow's exp(z), a ball rolling at 10 rad/s was called chattering above 0.08 s while runs at
// 0.1 s held its roll exact for 600 steps.
std::optional<double> backward_euler_growth(const Eigen::MatrixXd& hJ) {
  if (!hJ.allFinite()) return 1.0;
  const auto mu = eigenvalues(hJ);
  if (!mu) return std::nullopt;
  double growth = 1.0;
  for (const std::complex<double>& m : *mu) {
    if (m.real() > 0.0) growth = std::max(growth, 1.0 / std::abs(1.0 - m));
  }
  return growth;
}

// The implicit step (core/implicit_euler.hpp): x' = x + h F(x*; h), x* = x' in the solved
// entries and x in the states of clamped friction (P selects the solved ones), linearized:
// (I - h J P) dx' = (I + h J (I - P)) dx, its radius relative to backward_euler_growth. Backward
// Euler damps every decaying mode at any h, so what is left to find is the clamped friction
// states' explicit part. Group by group as above.
std::optional<double> implicit_step_radius(IslandSystem& sys, double h, bool friction_held,
                                           SiteLinearization& site,
                                           const std::vector<bool>& solved) {
  const int n = sys.size();
  auto J = jacobian(sys, h, friction_held, site.sparsity);
  if (!J) return std::nullopt;
  const Groups groups = coupled_groups({&*J}, n);
  std::vector<Eigen::MatrixXd> hJ(groups.size());
  std::vector<double> r(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::vector<int>& group = groups[g];
    const int m = static_cast<int>(group.size());
    hJ[g] = h * (*J)(group, group);
    Eigen::MatrixXd lhs = Eigen::MatrixXd::Identity(m, m);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Identity(m, m);
    for (int c = 0; c < m; ++c) {
      if (solved[static_cast<std::size_t>(sys.entry(group[static_cast<std::size_t>(c)]))]) {
        lhs.col(c) -= hJ[g].col(c);
      } else {
        rhs.col(c) += hJ[g].col(c);
      }
    }
    const auto radius = step_map_radius(lhs.partialPivLu().solve(rhs), site);
    if (!radius) return std::nullopt;
    r[g] = *radius;
  }
  // Divided by a growth of at least 1, a radius at most the threshold stays so: when no
  // group's exceeds it, the verdict needs no growth (and a growth with no answer would only
  // have made the whole radius no answer, which is as stable).
  const double largest = r.empty() ? 0.0 : *std::max_element(r.begin(), r.end());
  if (site.verdict_only && largest <= 1.0 + kUnstableGrowth) return largest;
  double radius = 0.0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto growth = backward_euler_growth(hJ[g]);
    if (!growth) return std::nullopt;
    radius = std::max(radius, r[g] / *growth);
  }
  return radius;
}

}  // namespace

std::vector<TimedState> sample_states(Network& network, const RunOptions& options, int per_regime) {
  // Pass 1: how many steps each regime lasts. Pass 2 (the same deterministic run): take
  // per_regime of them, evenly spread.
  std::map<std::size_t, long> steps_in;
  walk_run(network, options, [&](long, double, const Vec& x, double) {
    ++steps_in[network.regime_signature(x, options.dt)];
  });
  std::map<std::size_t, long> seen, taken;
  std::vector<TimedState> states;
  std::vector<long> rank;  // of each state among those taken from its regime (0: the first)
  // The energy monitor's headroom at each state, from the same budget the run's monitor
  // keeps (core/energy_budget.hpp), here updated at every step.
  EnergyBudget budget(network, options.energy_tolerance);
  // The monitor gives its first verdict at step kSettleObservations: a state before that is
  // judged with the headroom there (none is given if the run is shorter).
  double first_verdict_headroom = INFINITY;
  std::vector<std::size_t> before_verdict;
  walk_run(network, options, [&](long k, double t, const Vec& x, double work) {
    budget.observe(x, work);
    if (k == kSettleObservations) first_verdict_headroom = budget.headroom();
    const std::size_t regime = network.regime_signature(x, options.dt);
    const long total = steps_in[regime];
    const long index = seen[regime]++;
    // Taken where index * per_regime / total (integer division) moves on: per_regime steps
    // evenly spread, or every step of a regime shorter than that.
    const long n = std::max(1, per_regime);
    if (index == 0 || (index * n) / total != ((index - 1) * n) / total) {
      if (k < kSettleObservations) before_verdict.push_back(states.size());
      states.push_back({t, x, budget.headroom()});
      rank.push_back(taken[regime]++);
    }
  });
  for (std::size_t i : before_verdict) states[i].energy_headroom = first_verdict_headroom;
  // Bounded whatever the scene (a box bouncing on eight corners passes through hundreds of
  // regimes): every regime's first state before any regime's second, and so on; the
  // states of the last rank that fits only in part evenly spread over the run.
  if (states.size() > kMaxSampledStates) {
    std::vector<TimedState> kept;
    for (long r = 0; kept.size() < kMaxSampledStates; ++r) {
      std::vector<std::size_t> of_rank;
      for (std::size_t i = 0; i < states.size(); ++i) {
        if (rank[i] == r) of_rank.push_back(i);
      }
      const std::size_t room = kMaxSampledStates - kept.size();
      for (std::size_t k = 0; k < std::min(room, of_rank.size()); ++k) {
        const std::size_t pick = of_rank.size() <= room ? k : k * of_rank.size() / room;
        kept.push_back(std::move(states[of_rank[pick]]));
      }
    }
    states = std::move(kept);
  }
  std::sort(states.begin(), states.end(),
            [](const TimedState& a, const TimedState& b) { return a.t < b.t; });
  return states;
}

namespace {

// The sparsity of an island at its state: the entries that the system at several stage
// sizes, with and without friction held, and the kinematics move. Only which entries move
// matters here, so one forward difference per index is enough, also on a switching surface.
Sparsity state_sparsity(IslandSystem& sys) {
  const int n = sys.size();
  const Vec& x = sys.state();
  Eigen::MatrixXd pattern = Eigen::MatrixXd::Zero(n, n);
  Vec center(n), moved(n), plus(n);
  const auto mark = [&](const auto& F) {
    F(x, center);
    for (int i = 0; i < n; ++i) {
      plus = x;
      plus[i] += 1e-7 * std::max(std::abs(x[i]), 1e-3);
      F(plus, moved);
      for (int r = 0; r < n; ++r) {
        if (moved[r] != center[r] || !std::isfinite(moved[r])) pattern(r, i) = 1.0;
      }
    }
  };
  for (double tau : {1e-6, 1e-3, 1e-1}) {
    mark([&](const Vec& at, Vec& out) { sys.derivative(at, tau, out); });
    mark([&](const Vec& at, Vec& out) { sys.derivative_friction_held(at, tau, out); });
  }
  mark([&](const Vec& at, Vec& out) { sys.kinematics(at, out); });
  Sparsity sparsity;
  sparsity.rows.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (int r = 0; r < n; ++r) {
      if (pattern(r, i) != 0.0) sparsity.rows[static_cast<std::size_t>(i)].push_back(r);
    }
  }
  // Greedy coloring, the columns that move the most rows first (ties in index order): a
  // column joins the first color none of whose columns moves one of its rows.
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return sparsity.rows[static_cast<std::size_t>(a)].size() >
           sparsity.rows[static_cast<std::size_t>(b)].size();
  });
  std::vector<std::vector<char>> taken;  // per color, the rows its columns move
  for (int i : order) {
    const auto& rows = sparsity.rows[static_cast<std::size_t>(i)];
    std::size_t c = 0;
    for (; c < taken.size(); ++c) {
      if (std::none_of(rows.begin(), rows.end(),
                       [&](int r) { return taken[c][static_cast<std::size_t>(r)] != 0; })) {
        break;
      }
    }
    if (c == taken.size()) {
      taken.emplace_back(static_cast<std::size_t>(n), 0);
      sparsity.colors.emplace_back();
    }
    for (int r : rows) taken[c][static_cast<std::size_t>(r)] = 1;
    sparsity.colors[c].push_back(i);
  }
  for (auto& color : sparsity.colors) std::sort(color.begin(), color.end());
  for (const auto& block : irreducible_blocks(pattern)) {
    sparsity.eigen_work += std::pow(static_cast<double>(block.size()), 3.0);
  }
  return sparsity;
}

StepRadius island_step_radius(IslandSystem& sys, const std::string& integrator, double h,
                              SiteLinearization& site, const std::vector<bool>& solved) {
  auto radius = [&](bool held) -> std::optional<double> {
    switch (integrator_traits(integrator).method) {
      case Method::symplectic_euler:
        return symplectic_step_radius(sys, h, held, site);
      case Method::implicit_euler:
        return implicit_step_radius(sys, h, held, site, solved);
      case Method::explicit_rk:
        return rk_step_radius(sys, tableau_by_name(integrator), h, held, site);
      case Method::adaptive_rk4:
      case Method::sdirk:
        break;
    }
    throw std::invalid_argument(integrator + " has no fixed step to analyse");
  };
  StepRadius r;
  const auto full = radius(false);
  if (!full) return r;
  r.full = *full;
  r.friction_held = r.full;
  r.friction_cap = sys.network().friction_cap_energy(sys.whole_state(), &sys.island());
  if (r.full > 1.0 + kUnstableGrowth && r.friction_cap > 0.0) {
    const auto held = radius(true);
    if (!held) return r;
    r.friction_held = *held;
  }
  r.smooth = true;
  return r;
}

// The islands' radii as one answer that unstable_step() judges as it would judge each:
// the largest radii, and the largest friction cap among the islands that grow (an island's
// stuck friction can only hold its own). No answer only where no island has one.
void fold(StepRadius& all, StepRadius one) {
  if (!one.smooth) return;
  if (one.full <= 1.0 + kUnstableGrowth) one.friction_cap = 0.0;
  if (!all.smooth) {
    all = one;
    return;
  }
  all.full = std::max(all.full, one.full);
  all.friction_held = std::max(all.friction_held, one.friction_held);
  all.friction_cap = std::max(all.friction_cap, one.friction_cap);
}

// Scratch for the islands of one state (IslandSystem).
struct StateScratch {
  Vec full, out;
  explicit StateScratch(const Vec& x) : full(x), out(Vec::Zero(x.size())) {}
};

}  // namespace

int largest_island_states(const Network& network) {
  std::size_t largest = 0;
  for (const Island& island : find_islands(network)) {
    largest = std::max(largest, island.states.size());
  }
  return static_cast<int>(largest);
}

StepRadius step_radius(Network& network, const std::string& integrator, double t, const Vec& x,
                       double h) {
  // An island with too many states for the dense analysis gives no answer (state_sparsity
  // alone is n evaluations of an n x n pattern; at 6000 states it ran for minutes, issue 25).
  const std::vector<bool> solved = implicitly_solved_slots(network);
  StateScratch scratch(x);
  StepRadius all;
  for (const Island& island : find_islands(network)) {
    if (static_cast<int>(island.states.size()) > kMaxAnalysedStates) continue;
    IslandSystem sys(network, island, t, x, scratch.full, scratch.out);
    const Sparsity sparsity = state_sparsity(sys);
    SiteLinearization site;
    site.sparsity = &sparsity;
    fold(all, island_step_radius(sys, integrator, h, site, solved));
  }
  return all;
}

bool unstable_step(const StepRadius& r, double headroom, bool chatter_counts) {
  if (!r.smooth || r.full <= 1.0 + kUnstableGrowth) return false;
  const bool runaway = r.friction_held > 1.0 + kUnstableGrowth;
  return runaway || chatter_counts || r.friction_cap > headroom;
}

namespace {
struct SearchStopped {};  // unwinds the search from inside its lambdas

// One radius's work in AnalysisBudget units: an eigenvalue problem per irreducible block of
// the site's pattern (its size cubed; a block a bound settles costs less) and the Jacobian's
// n^2 entries.
double radius_work(const Sparsity& sparsity, int n) {
  return sparsity.eigen_work + static_cast<double>(n) * static_cast<double>(n);
}

// Which sampled states each island is analysed at. One island: all of them. Several: each
// island at the first and the last sampled state of each of its own regimes (its regime
// signature). The states sample the whole network's regimes, and with 1000 separate bodies
// nearly every state is a new combination of regimes that are each the same few per body.
std::vector<std::vector<std::size_t>> island_states(Network& network,
                                                    const std::vector<Island>& islands,
                                                    const std::vector<TimedState>& states,
                                                    double tau) {
  std::vector<std::vector<std::size_t>> chosen(islands.size());
  for (std::size_t k = 0; k < islands.size(); ++k) {
    if (islands.size() == 1) {
      for (std::size_t i = 0; i < states.size(); ++i) chosen[k].push_back(i);
      continue;
    }
    std::map<std::size_t, std::pair<std::size_t, std::size_t>> first_last;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const std::size_t regime = network.regime_signature(states[i].x, tau, &islands[k]);
      auto [it, fresh] = first_last.emplace(regime, std::make_pair(i, i));
      if (!fresh) it->second.second = i;
    }
    for (const auto& [regime, ends] : first_last) {
      chosen[k].push_back(ends.first);
      if (ends.second != ends.first) chosen[k].push_back(ends.second);
    }
    std::sort(chosen[k].begin(), chosen[k].end());
  }
  return chosen;
}
}  // namespace

StepLimit predict_step_limit(Network& network, const std::string& integrator,
                             const std::vector<TimedState>& states, double h_min, double h_max,
                             const std::atomic<bool>* stop, AnalysisBudget* budget) {
  if (!analysable(network)) {
    StepLimit skipped;
    skipped.skipped = true;
    return skipped;
  }
  const std::vector<Island> islands = find_islands(network);
  const std::vector<bool> solved = implicitly_solved_slots(network);
  const auto at_states = island_states(network, islands, states, 1e-3);
  // stable(h, chatter_counts): no sampled state has a mode growing faster than allowed in
  // any island; a mode only stuck friction carries counts where the monitor would see it,
  // or always if chatter_counts.
  double limiting_time = 0.0;
  // The two searches below (runaway, then chatter) visit the same grid: each radius is
  // computed once per island and state (a site).
  struct Site {
    std::size_t island, state;
    std::optional<Sparsity> sparsity;
    SiteLinearization linearization;  // what the steps tried here share
    std::map<double, StepRadius> radii;
  };
  std::vector<Site> sites;
  for (std::size_t k = 0; k < islands.size(); ++k) {
    for (std::size_t i : at_states[k]) sites.push_back({k, i, std::nullopt, {}, {}});
  }
  // In the order of the states, so that the search meets the earliest limiting state first.
  std::stable_sort(sites.begin(), sites.end(),
                   [](const Site& a, const Site& b) { return a.state < b.state; });
  std::vector<std::optional<StateScratch>> scratch(states.size());
  auto radius_at = [&](Site& site, double h) {
    auto it = site.radii.find(h);
    if (it != site.radii.end()) return it->second;
    const TimedState& s = states[site.state];
    auto& room = scratch[site.state];
    if (!room) room.emplace(s.x);
    IslandSystem sys(network, islands[site.island], s.t, s.x, room->full, room->out);
    if (!site.sparsity) site.sparsity = state_sparsity(sys);
    if (budget != nullptr) {
      budget->spent += radius_work(*site.sparsity, sys.size());
      if (budget->spent > budget->limit) throw SearchStopped{};
    }
    site.linearization.sparsity = &*site.sparsity;
    site.linearization.verdict_only = true;
    StepRadius r = island_step_radius(sys, integrator, h, site.linearization, solved);
    if (r.full <= 1.0 + kUnstableGrowth) r.friction_cap = 0.0;
    site.radii.emplace(h, r);
    return r;
  };
  auto stable = [&](double h, bool chatter_counts) {
    for (Site& site : sites) {
      if (stop != nullptr && stop->load(std::memory_order_relaxed)) throw SearchStopped{};
      const TimedState& s = states[site.state];
      if (unstable_step(radius_at(site, h), s.energy_headroom, chatter_counts)) {
        limiting_time = s.t;
        return false;
      }
    }
    return true;
  };
  // The smallest unstable step on a grid of ratio 10^0.1 from h_min up, then bisection below
  // it: stability can come back above a window of instability (a stuck friction spring
  // under RK4), and the first window is the one that matters.
  auto first_limit = [&](bool chatter_counts, double& time) -> std::optional<double> {
    double lo = 0.0;
    // The grid is 10^(k/10) whatever h_min is (h_min rounded down onto it), so that a check
    // from 1e-9 and a guard from dt/32 visit the same steps and agree on the limits.
    const int first = static_cast<int>(std::floor(10.0 * std::log10(h_min) + 1e-9));
    for (int k = first;; ++k) {
      const double h = std::min(std::pow(10.0, k / 10.0), h_max);  // the last point is h_max
      if (stable(h, chatter_counts)) {
        if (h >= h_max) break;
        lo = h;
        continue;
      }
      if (lo == 0.0) {
        time = limiting_time;
        return 0.0;  // unstable at every step size tried
      }
      double hi = h;
      time = limiting_time;
      while (hi / lo > 1.001) {
        const double mid = std::sqrt(lo * hi);
        if (stable(mid, chatter_counts)) {
          lo = mid;
        } else {
          hi = mid;
          time = limiting_time;
        }
      }
      return lo;
    }
    return std::nullopt;  // stable up to h_max
  };
  StepLimit limit;
  double chatter_time = 0.0;
  std::optional<double> runaway, chatter;
  try {
    runaway = first_limit(false, limit.limiting_time);
    chatter = first_limit(true, chatter_time);
  } catch (const SearchStopped&) {
    limit.interrupted = true;
    limit.over_budget = budget != nullptr && budget->spent > budget->limit;
    return limit;
  }
  limit.unbounded = !runaway.has_value();
  limit.max_step = runaway.value_or(h_max);
  limit.chatter_free_step = chatter.value_or(h_max);
  return limit;
}

}  // namespace stiction::core
