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

namespace {

// Rows first_row .. end_row - 1 of every column j of x (n x n) less the panel's sum
// a(r, first_col .. first_col + W - 1) x(first_col .., j), taken from zero in column order
// and added times -1, as Eigen's gebp kernel does; W fixed so that the loop over the rows
// is vectorized (each row's sum keeps its order).
template <int W>
void subtract_panel(const double* a, double* x, int n, int first_row, int end_row, int first_col) {
  for (int j = 0; j < n; ++j) {
    double* __restrict column = x + static_cast<std::ptrdiff_t>(j) * n;
    double b[W];
    const double* __restrict panel[W];
    for (int c = 0; c < W; ++c) {
      b[c] = column[first_col + c];
      panel[c] = a + static_cast<std::ptrdiff_t>(first_col + c) * n;
    }
    for (int r = first_row; r < end_row; ++r) {
      double sum = 0.0;
      for (int c = 0; c < W; ++c) sum += panel[c][r] * b[c];
      column[r] = sum * -1.0 + column[r];
    }
  }
}

void subtract_panel(const double* a, double* x, int n, int first_row, int end_row, int first_col,
                    int width) {
  if (first_row >= end_row) return;
  switch (width) {
    case 1:
      return subtract_panel<1>(a, x, n, first_row, end_row, first_col);
    case 2:
      return subtract_panel<2>(a, x, n, first_row, end_row, first_col);
    case 3:
      return subtract_panel<3>(a, x, n, first_row, end_row, first_col);
    case 4:
      return subtract_panel<4>(a, x, n, first_row, end_row, first_col);
    default:
      for (int j = 0; j < n; ++j) {
        for (int r = first_row; r < end_row; ++r) {
          double sum = 0.0;
          for (int c = first_col; c < first_col + width; ++c) {
            sum += a[r + static_cast<std::ptrdiff_t>(c) * n] *
                   x[c + static_cast<std::ptrdiff_t>(j) * n];
          }
          x[r + static_cast<std::ptrdiff_t>(j) * n] =
              sum * -1.0 + x[r + static_cast<std::ptrdiff_t>(j) * n];
        }
      }
  }
}

}  // namespace

void small_inverse(const Eigen::MatrixXd& matrix, Eigen::MatrixXd& lu, Eigen::MatrixXd& inverse) {
  const int n = static_cast<int>(matrix.rows());
  if (n > kSmallInverseUnknowns || matrix.cols() != n) {
    throw std::invalid_argument("small_inverse: a square matrix of at most 16 rows");
  }
  lu = matrix;
  double* const a = lu.data();
  const auto at = [&](int i, int j) -> double& { return a[i + j * n]; };
  // PartialPivLU's unblocked_lu: the first largest |entry| of the column (at or below the
  // diagonal) is the pivot; a zero column is left, its swap still recorded.
  int swaps[kSmallInverseUnknowns];
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    double biggest = std::abs(at(k, k));
    for (int i = k + 1; i < n; ++i) {
      const double score = std::abs(at(i, k));
      if (score > biggest) {
        biggest = score;
        pivot = i;
      }
    }
    swaps[k] = pivot;
    if (biggest != 0.0) {
      if (pivot != k) {
        for (int j = 0; j < n; ++j) std::swap(at(k, j), at(pivot, j));
      }
      const double diagonal = at(k, k);
      for (int i = k + 1; i < n; ++i) at(i, k) /= diagonal;
    }
    for (int j = k + 1; j < n; ++j) {
      const double u = at(k, j);
      for (int i = k + 1; i < n; ++i) at(i, j) -= at(i, k) * u;
    }
  }
  // P times the identity.
  inverse.setIdentity(n, n);
  double* const x = inverse.data();
  const auto out = [&](int i, int j) -> double& { return x[i + j * n]; };
  for (int k = 0; k < n; ++k) {
    if (swaps[k] == k) continue;
    for (int j = 0; j < n; ++j) std::swap(out(k, j), out(swaps[k], j));
  }
  // Eigen's triangular_solve_matrix: panels of max(mr, nr) columns (4 on SSE2 doubles);
  // inside a panel column by column, the rows past it by the panel's sum, taken from zero in
  // column order and added times -1 (gebp's alpha).
  using Traits = Eigen::internal::gebp_traits<double, double>;
  constexpr int kPanel = std::max<int>(Traits::mr, Traits::nr);
  for (int k1 = 0; k1 < n; k1 += kPanel) {  // L, unit lower, from the top
    const int width = std::min(n - k1, kPanel);
    for (int i = k1; i < k1 + width; ++i) {
      for (int j = 0; j < n; ++j) {
        const double b = out(i, j);
        for (int r = i + 1; r < k1 + width; ++r) out(r, j) -= b * at(r, i);
      }
    }
    subtract_panel(lu.data(), x, n, k1 + width, n, k1, width);
  }
  for (int k1 = 0; k1 < n; k1 += kPanel) {  // U, from the bottom
    const int width = std::min(n - k1, kPanel);
    const int top = n - k1 - width;  // the panel's first row
    for (int i = n - 1 - k1; i >= top; --i) {
      const double reciprocal = 1.0 / at(i, i);  // Eigen multiplies by it
      for (int j = 0; j < n; ++j) {
        out(i, j) *= reciprocal;
        const double b = out(i, j);
        for (int r = top; r < i; ++r) out(r, j) -= b * at(r, i);
      }
    }
    subtract_panel(lu.data(), x, n, 0, top, top, width);
  }
}

ImplicitEulerStepper::ImplicitEulerStepper(int state_dim, double dt)
    : dt_(dt),
      start_(Vec::Zero(state_dim)),
      iterate_(Vec::Zero(state_dim)),
      eval_(Vec::Zero(state_dim)),
      f_(Vec::Zero(state_dim)),
      probe_(Vec::Zero(state_dim)),
      f_probe_(Vec::Zero(state_dim)),
      f_star_(Vec::Zero(state_dim)),
      last_eval_(Vec::Zero(state_dim)),
      stage_(Vec::Zero(state_dim)) {}

void ImplicitEulerStepper::prepare(Network& network) {
  detached_.assign(network.impedances().size(), 0);
  for (int i = 0; i < static_cast<int>(network.impedances().size()); ++i) {
    const Capabilities& c = network.capabilities(i);
    if (detach_contacts_ && c.contact != nullptr && network.map_of(i).admittances().size() >= 2) {
      separable_.push_back(i);
    }
  }
  for (StepGroup& g : groups_) {
    g.separable.clear();
    for (int i : separable_) {
      if (std::binary_search(g.part.impedances.begin(), g.part.impedances.end(), i)) {
        g.separable.push_back(i);
      }
    }
  }
  build_islands(network);
  prepared_ = true;
}

void ImplicitEulerStepper::set_step_groups(const std::vector<Island>& groups) {
  const int dim = static_cast<int>(start_.size());
  group_of_state_.assign(static_cast<std::size_t>(dim), -1);
  groups_.clear();
  for (const Island& part : groups) {
    StepGroup g;
    g.part = part;
    g.runs = runs_of(part.states);
    g.share = static_cast<double>(part.states.size()) / std::max(1, dim);
    for (int e : part.states) {
      group_of_state_[static_cast<std::size_t>(e)] = static_cast<int>(groups_.size());
    }
    groups_.push_back(std::move(g));
  }
}

void ImplicitEulerStepper::copy_runs(const std::vector<Run>& runs, const Vec& from, Vec& to) {
  for (const Run& run : runs) {
    const double* source = from.data() + run.entry;
    double* target = to.data() + run.entry;
    for (int k = 0; k < run.length; ++k) target[k] = source[k];
  }
}

void ImplicitEulerStepper::build_islands(Network& network) {
  const std::vector<bool> solved = implicitly_solved_slots(network);
  const double dim = std::max(1, network.state_dim());
  std::vector<IslandSolve> previous = std::move(islands_);
  islands_.clear();
  // The old islands by their first state entry, to keep the matrices of unchanged ones.
  std::vector<int> old_at(static_cast<std::size_t>(network.state_dim()), -1);
  for (std::size_t k = 0; k < previous.size(); ++k) {
    old_at[static_cast<std::size_t>(previous[k].island.states.front())] = static_cast<int>(k);
  }
  for (Island& island : find_islands(network, &detached_)) {
    const int old = old_at[static_cast<std::size_t>(island.states.front())];
    if (old >= 0) {
      IslandSolve& kept = previous[static_cast<std::size_t>(old)];
      if (kept.island.states == island.states && kept.island.impedances == island.impedances) {
        islands_.push_back(std::move(kept));
        continue;
      }
    }
    IslandSolve s;
    s.island = std::move(island);
    for (int e : s.island.states) {
      if (solved[static_cast<std::size_t>(e)]) s.solved.push_back(e);
    }
    for (int i : s.island.impedances) {
      const Capabilities& c = network.capabilities(i);
      if (c.friction != nullptr && c.slip != nullptr) s.friction_elements.push_back(i);
    }
    s.state_runs = runs_of(s.island.states);
    s.solved_runs = runs_of(s.solved);
    s.share = static_cast<double>(s.island.states.size()) / dim;
    const auto n = static_cast<Eigen::Index>(s.solved.size());
    set_pattern(network, s);
    s.matrix = Eigen::MatrixXd::Identity(s.sparse ? 0 : n, s.sparse ? 0 : n);
    s.lu = Eigen::PartialPivLU<Eigen::MatrixXd>(s.sparse ? 0 : n);
    s.residual = Vec::Zero(n);
    s.delta = Vec::Zero(n);
    s.probe_delta = Vec::Zero(n);
    s.scale = Vec::Zero(n);
    islands_.push_back(std::move(s));
  }
  for (StepGroup& g : groups_) g.islands.clear();
  for (std::size_t k = 0; k < islands_.size() && !groups_.empty(); ++k) {
    const int g = group_of_state_[static_cast<std::size_t>(islands_[k].island.states.front())];
    if (g < 0) throw std::logic_error("implicit: an island outside every step group");
    groups_[static_cast<std::size_t>(g)].islands.push_back(static_cast<int>(k));
  }
}

std::vector<ImplicitEulerStepper::Run> ImplicitEulerStepper::runs_of(
    const std::vector<int>& entries) {
  std::vector<Run> runs;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const int e = entries[k];
    if (!runs.empty() && runs.back().entry + runs.back().length == e) {
      ++runs.back().length;
    } else {
      runs.push_back({e, static_cast<int>(k), 1});
    }
  }
  return runs;
}

void ImplicitEulerStepper::copy_states(const IslandSolve& s, const Vec& from, Vec& to) {
  for (const Run& run : s.state_runs) {
    const double* source = from.data() + run.entry;
    double* target = to.data() + run.entry;
    for (int k = 0; k < run.length; ++k) target[k] = source[k];
  }
}

void ImplicitEulerStepper::update_detached(Network& network, const Vec& x, double h,
                                           const std::vector<int>* contacts) {
  bool changed = false;
  for (int i : contacts != nullptr ? *contacts : separable_) {
    const NormalContact* contact = network.capabilities(i).contact;
    const ConstVecRef x_hat = network.impedance_input(i, x);
    const double gap = contact->gap(x_hat);
    const char apart = gap > 2.0 * h * contact->approach_speed(x_hat) ? 1 : 0;  // NaN: no
    char& flag = detached_[static_cast<std::size_t>(i)];
    changed = changed || flag != apart;
    flag = apart;
  }
  if (changed) build_islands(network);
}

bool ImplicitEulerStepper::attach_closed(Network& network, const Vec& x,
                                         const std::vector<int>* contacts) {
  bool closed = false;
  for (int i : contacts != nullptr ? *contacts : separable_) {
    char& flag = detached_[static_cast<std::size_t>(i)];
    if (flag == 0) continue;
    const double gap = network.capabilities(i).contact->gap(network.impedance_input(i, x));
    if (!(gap > 0.0)) {
      flag = 0;
      closed = true;
    }
  }
  if (closed) build_islands(network);
  return closed;
}

void ImplicitEulerStepper::count_part_evaluation(const IslandSolve& s) {
  part_evaluations_ += s.share;
  evaluations_ = whole_evaluations_ + static_cast<long>(part_evaluations_);
}

void ImplicitEulerStepper::evaluate_part(Network& network, IslandSolve& s, double t, const Vec& y,
                                         double h, Vec& out) {
  network.derivative_part(t, y.data(), h, out.data(), s.island);
  count_part_evaluation(s);
}

void ImplicitEulerStepper::evaluate_star(Network& network, const Island& star, double t,
                                         const Vec& y, double h, Vec& out) {
  network.derivative_part(t, y.data(), h, out.data(), star);
  part_evaluations_ +=
      static_cast<double>(star.states.size()) / static_cast<double>(network.state_dim());
  evaluations_ = whole_evaluations_ + static_cast<long>(part_evaluations_);
}

std::string in_island_of(const Network& network, const Island& part) {
  std::string name;
  if (!part.admittances.empty()) {
    name = network.admittances()[static_cast<std::size_t>(part.admittances.front())]->name();
  } else if (!part.impedances.empty()) {
    name = network.impedances()[static_cast<std::size_t>(part.impedances.front())]->name();
  }
  std::string text = " in the island of '";
  text += name;
  text += "'";
  return text;
}

std::string ImplicitEulerStepper::describe(const Network& network, const IslandSolve& s) const {
  if (islands_.size() == 1) return "";
  std::ostringstream text;
  text << in_island_of(network, s.island) << " (" << s.island.admittances.size() << " bodies, "
       << s.island.impedances.size() << " elements)";
  return text.str();
}

bool ImplicitEulerStepper::solve_islands(Network& network, double t, double h, Vec& x,
                                         bool may_split) {
  for (IslandSolve& s : islands_) {
    if (solve(network, s, t, h, x, true) || (may_split && split(network, s, t, h, x, 1))) continue;
    failed_ = &s;
    return false;
  }
  return true;
}

double ImplicitEulerStepper::advance(Network& network, double t, double limit, Vec& x) {
  if (!prepared_) prepare(network);
  const double h = std::min(dt_, limit);
  if (!separable_.empty()) {
    update_detached(network, x, h);
    step_start_ = x;
  }
  for (;;) {
    // F at the step's start, whole: every island's first Newton residual, and (for the run
    // loop) the evaluation that reads the state's own slips.
    network.derivative(t + h, x, h, f_);
    evaluations_ = ++whole_evaluations_ + static_cast<long>(part_evaluations_);
    if (!solve_islands(network, t, h, x, true)) {
      std::ostringstream message;
      message << "implicit: Newton's iteration did not converge" << describe(network, *failed_)
              << " in a step of " << h << " s at t = " << t << " s, nor in steps "
              << (1 << kMaxSplits)
              << " times shorter (a stiff element switching faster than the step can follow, "
                 "or a state that is running away)";
      throw std::runtime_error(message.str());
    }
    // A detached contact that closed after all: the step again, with it attached.
    if (separable_.empty() || !attach_closed(network, x)) return h;
    x = step_start_;
  }
}

bool ImplicitEulerStepper::solve_stage(Network& network, double t, double h, Vec& x) {
  if (!prepared_) prepare(network);
  if (!separable_.empty()) update_detached(network, x, h);
  for (;;) {
    network.derivative(t + h, x, h, f_);
    evaluations_ = ++whole_evaluations_ + static_cast<long>(part_evaluations_);
    if (keep_start_slope_) f_start_ = f_;
    stage_ = x;
    if (!solve_islands(network, t, h, stage_, false)) return false;
    if (separable_.empty() || !attach_closed(network, stage_)) break;
  }
  x = stage_;
  return true;
}

bool ImplicitEulerStepper::solve_stage(Network& network, double t, double h, Vec& x, int group) {
  if (!prepared_) prepare(network);
  StepGroup& g = groups_.at(static_cast<std::size_t>(group));
  if (!g.separable.empty()) update_detached(network, x, h, &g.separable);
  if (keep_start_slope_ && f_start_.size() != f_.size()) f_start_ = Vec::Zero(f_.size());
  for (;;) {
    // The group's first evaluation: every island's first residual in it.
    network.derivative_part(t + h, x.data(), h, f_.data(), g.part);
    part_evaluations_ += g.share;
    evaluations_ = whole_evaluations_ + static_cast<long>(part_evaluations_);
    if (keep_start_slope_) copy_runs(g.runs, f_, f_start_);
    copy_runs(g.runs, x, stage_);
    for (int k : g.islands) {
      IslandSolve& s = islands_[static_cast<std::size_t>(k)];
      if (!solve(network, s, t, h, stage_, true)) {
        failed_ = &s;
        return false;
      }
    }
    if (g.separable.empty() || !attach_closed(network, stage_, &g.separable)) break;
  }
  copy_runs(g.runs, stage_, x);
  return true;
}

bool ImplicitEulerStepper::apply_inverse(Vec& v, int group) {
  return apply_inverse_over(v, &groups_.at(static_cast<std::size_t>(group)).islands);
}

void ImplicitEulerStepper::set_scale(IslandSolve& s, const Vec& x) {
  for (const Run& run : s.solved_runs) {
    const double* at = x.data() + run.entry;
    double* scale = s.scale.data() + run.index;
    for (int k = 0; k < run.length; ++k) scale[k] = kRelative * std::abs(at[k]) + kAbsolute;
  }
}

double ImplicitEulerStepper::scaled_norm(const IslandSolve& s, const Vec& correction) {
  double norm = 0.0;
  for (Eigen::Index r = 0; r < correction.size(); ++r) {
    norm = std::max(norm, std::abs(correction[r]) / s.scale[r]);
  }
  return std::isfinite(norm) ? norm : std::numeric_limits<double>::infinity();
}

void ImplicitEulerStepper::set_pattern(Network& network, IslandSolve& s) const {
  const auto n = static_cast<Eigen::Index>(s.solved.size());
  if (compress_) {
    s.pattern = jacobian_pattern(network, s.island, s.solved, stars_);
  } else {
    s.pattern = JacobianPattern{};
    std::vector<int> all(static_cast<std::size_t>(n));
    for (Eigen::Index k = 0; k < n; ++k) all[static_cast<std::size_t>(k)] = static_cast<int>(k);
    for (Eigen::Index k = 0; k < n; ++k) s.pattern.groups.push_back({static_cast<int>(k)});
    s.pattern.group_star.assign(static_cast<std::size_t>(n), -1);
    s.pattern.rows.assign(static_cast<std::size_t>(n), all);
  }
  s.sparse =
      n >= sparse_unknowns_ && static_cast<double>(s.pattern.nonzeros()) <=
                                   kSparseFill * static_cast<double>(n) * static_cast<double>(n);
  if (!s.sparse) return;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(s.pattern.nonzeros()));
  for (Eigen::Index k = 0; k < n; ++k) {
    for (int r : s.pattern.rows[static_cast<std::size_t>(k)]) entries.emplace_back(r, k, 0.0);
  }
  s.sparse_matrix.resize(n, n);
  s.sparse_matrix.setFromTriplets(entries.begin(), entries.end());
  s.sparse_matrix.makeCompressed();
  // refresh_matrix writes column k's q-th entry for the pattern's q-th row of k: the
  // structure must list them in that order.
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto& rows = s.pattern.rows[static_cast<std::size_t>(k)];
    const int first = s.sparse_matrix.outerIndexPtr()[k];
    for (std::size_t q = 0; q < rows.size(); ++q) {
      if (s.sparse_matrix.innerIndexPtr()[first + static_cast<int>(q)] != rows[q]) {
        throw std::logic_error("implicit: a sparse matrix's structure differs from its pattern");
      }
    }
  }
  s.sparse_lu = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>>>();
  s.sparse_lu->analyzePattern(s.sparse_matrix);
}

int ImplicitEulerStepper::sparse_islands() const {
  int count = 0;
  for (const IslandSolve& s : islands_) count += s.sparse && s.sparse_factored ? 1 : 0;
  return count;
}

void ImplicitEulerStepper::refresh_matrix(Network& network, IslandSolve& s, double t_eval,
                                          double h) {
  const auto n = static_cast<Eigen::Index>(s.solved.size());
  if (s.sparse) {
    s.sparse_matrix.coeffs().setZero();
  } else {
    s.matrix.setIdentity();
  }
  copy_states(s, eval_, probe_);
  column_steps_.resize(static_cast<std::size_t>(n));
  double* values = s.sparse ? s.sparse_matrix.valuePtr() : nullptr;
  const int* outer = s.sparse ? s.sparse_matrix.outerIndexPtr() : nullptr;
  int star_at_rest = -1;  // the star whose unperturbed rates f_star_ holds
  for (std::size_t g = 0; g < s.pattern.groups.size(); ++g) {
    const std::vector<int>& group = s.pattern.groups[g];
    // A star (core/jacobian_pattern.hpp) is evaluated unperturbed too, once for all the
    // groups of its colour; its rows are differenced against that.
    const int star = s.pattern.group_star[g];
    if (star >= 0 && star != star_at_rest) {
      evaluate_star(network, s.pattern.stars[static_cast<std::size_t>(star)], t_eval, probe_, h,
                    f_star_);
      star_at_rest = star;
    }
    const Vec& at_rest = star >= 0 ? f_star_ : f_;
    for (int k : group) {
      const int j = s.solved[static_cast<std::size_t>(k)];
      // About sqrt(eps) relative, taken as the difference actually stored, so that the
      // quotient divides by the step the state really made.
      probe_[j] += 1.5e-8 * std::max(std::abs(eval_[j]), 1e-3);
      column_steps_[static_cast<std::size_t>(k)] = probe_[j] - eval_[j];
    }
    if (star >= 0) {
      evaluate_star(network, s.pattern.stars[static_cast<std::size_t>(star)], t_eval, probe_, h,
                    f_probe_);
    } else {
      evaluate_part(network, s, t_eval, probe_, h, f_probe_);
    }
    ++matrix_evaluations_;
    for (int k : group) {
      const int j = s.solved[static_cast<std::size_t>(k)];
      probe_[j] = eval_[j];
      const double delta = column_steps_[static_cast<std::size_t>(k)];
      const auto& rows = s.pattern.rows[static_cast<std::size_t>(k)];
      for (std::size_t q = 0; q < rows.size(); ++q) {
        const int r = rows[q];
        const int i = s.solved[static_cast<std::size_t>(r)];
        const double change = h * (f_probe_[i] - at_rest[i]) / delta;
        if (values != nullptr) {
          values[outer[k] + static_cast<int>(q)] = (r == k ? 1.0 : 0.0) - change;
        } else {
          s.matrix(r, k) -= change;
        }
      }
    }
  }
  if (!s.sparse && n <= kSmallInverseUnknowns) {
    // The same inverse as the branch below, for a fraction of its cost (small_inverse).
    small_inverse(s.matrix, s.small_lu, s.inverse);
  } else if (s.sparse) {
    s.sparse_lu->factorize(s.sparse_matrix);
    s.sparse_factored = s.sparse_lu->info() == Eigen::Success;
    // A singular pivot under the sparse ordering: the dense LU with partial pivoting takes
    // this matrix (as it takes every matrix of a small island).
    if (!s.sparse_factored) s.lu.compute(Eigen::MatrixXd(s.sparse_matrix));
  } else {
    s.lu.compute(s.matrix);
  }
  // A small island's corrections are one product with the inverse: Eigen's two triangular
  // solves cost more in their blocking than in their arithmetic at 13 unknowns (28% of a
  // step of 1000 spheres). Simplified Newton corrects the inverse's rounding as it does
  // the matrix's age.
  if (!s.sparse && n > kSmallInverseUnknowns && n <= kInverseUnknowns) s.inverse = s.lu.inverse();
  s.lu_valid = true;
  s.lu_h = h;
  ++matrices_formed_;
}

void ImplicitEulerStepper::evaluate_iterate(Network& network, IslandSolve& s, double t_end,
                                            double h) {
  // x*: the solved entries from the iterate, the clamped friction states from the start.
  copy_states(s, start_, eval_);
  for (const Run& run : s.solved_runs) {
    const double* iterate = iterate_.data() + run.entry;
    double* target = eval_.data() + run.entry;
    for (int k = 0; k < run.length; ++k) target[k] = iterate[k];
  }
  evaluate_part(network, s, t_end, eval_, h, f_);
  for (const Run& run : s.solved_runs) {
    const double *iterate = iterate_.data() + run.entry, *start = start_.data() + run.entry,
                 *f = f_.data() + run.entry;
    double* residual = s.residual.data() + run.index;
    for (int k = 0; k < run.length; ++k) residual[k] = iterate[k] - start[k] - h * f[k];
  }
}

bool ImplicitEulerStepper::move_into_stuck_band(Network& network, IslandSolve& s, double h) {
  // Along the last Newton step (from last_eval_ to eval_), the first point where a sliding
  // element's slip, reversed at the step's end, reaches the middle of its stuck band.
  double alpha = 1.0;
  for (int i : s.friction_elements) {
    const Capabilities& c = network.capabilities(i);
    const Slot slot = network.impedance_slot(i);
    const auto y = start_.segment(slot.state_offset, slot.state_size);
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
  for (const Run& run : s.solved_runs) {
    double* iterate = iterate_.data() + run.entry;
    const double* last = last_eval_.data() + run.entry;
    for (int k = 0; k < run.length; ++k) iterate[k] = last[k] + alpha * (iterate[k] - last[k]);
  }
  return true;
}

bool ImplicitEulerStepper::solve(Network& network, IslandSolve& s, double t, double h, Vec& x,
                                 bool start_known) {
  const double t_end = t + h;
  copy_states(s, x, start_);
  copy_states(s, x, eval_);
  copy_states(s, x, iterate_);
  set_scale(s, start_);
  if (!start_known) evaluate_part(network, s, t_end, x, h, f_);
  for (const Run& run : s.solved_runs) {
    const double* f = f_.data() + run.entry;
    double* residual = s.residual.data() + run.index;
    for (int k = 0; k < run.length; ++k) residual[k] = -h * f[k];
  }
  int formed = 0;  // matrices formed during this step
  // A step that differs from the matrix's only in its last bits (a run loop's h = target - t
  // after t has summed many steps) keeps the matrix: I - h J barely changes, and forming it
  // anew each time such an h came round was 0.6 matrices per island and step on 1000
  // sliding spheres, most of their cost.
  if (!s.lu_valid || std::abs(s.lu_h - h) > kSameStep * h) {
    refresh_matrix(network, s, t_end, h);
    ++formed;
  }
  correct(s);
  double previous = scaled_norm(s, s.delta);
  int moves = 0, halvings = 0;
  for (int k = 0; k < kMaxIterations; ++k) {
    copy_states(s, eval_, last_eval_);
    for (const Run& run : s.solved_runs) {
      double* iterate = iterate_.data() + run.entry;
      const double* delta = s.delta.data() + run.index;
      for (int k = 0; k < run.length; ++k) iterate[k] -= delta[k];
    }
    network.solve_kinematics(start_, iterate_, h, &s.island);
    evaluate_iterate(network, s, t_end, h);
    // Converged when the next Newton correction is below the tolerance: measured on the
    // correction, not the residual, since a stiff element's residual carries its stiffness
    // times the rounding of the position (K = 1e7 N/m turns 3e-17 m into 1e-9 m/s^2).
    correct(s);
    double norm = scaled_norm(s, s.delta);
    if (norm > 0.1 * previous && norm > 1.0 && std::isfinite(norm)) {
      // Slow contraction. Either the step crossed a friction element's stuck band (Newton
      // from the sliding side overshoots it, from the other side back: a cycle around the
      // kinks of the clamp), so the iterate goes to the band's middle first; or the matrix
      // is from another regime (an element stuck, sliding, touching or lifting off since)
      // or stale (a contact that a step opens or closes: the iteration cycles between the
      // two sides of its kink with a matrix from either). Either way the matrix is formed
      // anew at the iterate.
      bool moved = moves < kMaxBandMoves && move_into_stuck_band(network, s, h);
      if (moved) {
        ++moves;
      } else if (norm > previous && halvings < kMaxHalvings) {
        // Growing: the step jumped across kinks the band move does not know (several
        // corners of a tumbling box at once). Half of it, to break the cycle.
        for (const Run& run : s.solved_runs) {
          double* iterate = iterate_.data() + run.entry;
          const double* last = last_eval_.data() + run.entry;
          for (int k = 0; k < run.length; ++k) iterate[k] = 0.5 * (last[k] + iterate[k]);
        }
        ++halvings;
        moved = true;
      }
      if (moved) evaluate_iterate(network, s, t_end, h);
      if (moved || formed < kMaxMatricesPerStep) {
        refresh_matrix(network, s, t_end, h);
        ++formed;
        correct(s);
        norm = scaled_norm(s, s.delta);
      }
    }
    // A correction that no longer shrinks, within kRoundingFloor tolerances, is rounding:
    // an entry coupled to stiff springs (a tumbling box's angular velocity) jitters by a few
    // 1e-13 from one iterate to the next however exact the matrix.
    const bool at_floor = norm <= kRoundingFloor && norm > 0.5 * previous;
    if (norm <= 1.0 || at_floor) {
      // Every entry moves by h times F at the solution: the positions by the new velocities
      // and a stuck friction state by the slip velocity there, alike (no drift).
      for (const Run& run : s.state_runs) {
        const double *start = start_.data() + run.entry, *f = f_.data() + run.entry;
        double* to = x.data() + run.entry;
        for (int k = 0; k < run.length; ++k) to[k] = start[k] + h * f[k];
      }
      network.project(x, &s.island);
      return true;
    }
    if (!std::isfinite(norm)) return false;
    previous = norm;
  }
  return false;
}

void ImplicitEulerStepper::correct(IslandSolve& s) {
  if (s.sparse && s.sparse_factored) {
    s.delta = s.sparse_lu->solve(s.residual);
  } else if (!s.sparse && s.residual.size() <= kInverseUnknowns) {
    // delta = inverse * residual, column by column: each entry sums its products in column
    // order from zero, as Eigen's matrix-vector kernel does (so the same bits), without
    // that kernel's dispatch and blocking, which cost more than the 169 products of a body.
    const int n = static_cast<int>(s.residual.size());
    const double* inverse = s.inverse.data();
    const double* residual = s.residual.data();
    double* delta = s.delta.data();
    // Eight rows at a time, their sums in four pairs held in registers over the columns
    // (independent chains of additions, as in Eigen's kernel), then two, then one.
    using Pair = Eigen::Array2d;
    const auto pair_at = [](const double* at) { return Eigen::Map<const Pair>(at); };
    int i = 0;
    for (; i + 8 <= n; i += 8) {
      Pair a = Pair::Zero(), b = Pair::Zero(), c = Pair::Zero(), d = Pair::Zero();
      const double* column = inverse + i;
      for (int j = 0; j < n; ++j, column += n) {
        const double r = residual[j];
        a += pair_at(column) * r;
        b += pair_at(column + 2) * r;
        c += pair_at(column + 4) * r;
        d += pair_at(column + 6) * r;
      }
      Eigen::Map<Pair>(delta + i) = a;
      Eigen::Map<Pair>(delta + i + 2) = b;
      Eigen::Map<Pair>(delta + i + 4) = c;
      Eigen::Map<Pair>(delta + i + 6) = d;
    }
    for (; i + 2 <= n; i += 2) {
      Pair a = Pair::Zero();
      const double* column = inverse + i;
      for (int j = 0; j < n; ++j, column += n) a += pair_at(column) * residual[j];
      Eigen::Map<Pair>(delta + i) = a;
    }
    for (; i < n; ++i) {
      double a = 0.0;
      const double* column = inverse + i;
      for (int j = 0; j < n; ++j, column += n) a += column[0] * residual[j];
      delta[i] = a;
    }
  } else {
    s.delta.noalias() = s.lu.solve(s.residual);
  }
}

bool ImplicitEulerStepper::apply_inverse(Vec& v) { return apply_inverse_over(v, nullptr); }

bool ImplicitEulerStepper::apply_inverse_over(Vec& v, const std::vector<int>* listed) {
  const std::size_t count = listed != nullptr ? listed->size() : islands_.size();
  const auto island = [&](std::size_t k) -> IslandSolve& {
    return islands_[listed != nullptr ? static_cast<std::size_t>((*listed)[k]) : k];
  };
  for (std::size_t k = 0; k < count; ++k) {
    if (!island(k).lu_valid) return false;
  }
  for (std::size_t k = 0; k < count; ++k) {
    IslandSolve& s = island(k);
    for (Eigen::Index r = 0; r < s.residual.size(); ++r) {
      s.residual[r] = v[s.solved[static_cast<std::size_t>(r)]];
    }
    correct(s);
    for (Eigen::Index r = 0; r < s.delta.size(); ++r)
      v[s.solved[static_cast<std::size_t>(r)]] = s.delta[r];
  }
  return true;
}

bool ImplicitEulerStepper::split(Network& network, IslandSolve& s, double t, double h, Vec& x,
                                 int depth) {
  if (depth > kMaxSplits) return false;
  const double half = 0.5 * h;
  for (int part = 0; part < 2; ++part) {
    const double at = t + part * half;
    if (!solve(network, s, at, half, x, false) && !split(network, s, at, half, x, depth + 1)) {
      return false;
    }
  }
  return true;
}

}  // namespace stiction::core
