#include "core/network.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace stiction::core {
namespace {

// Psi, the impedance and Phi through their interfaces, x_hat and u handed over in the
// network's vectors. The capturing twin (kCapture) also copies x_hat and the impedance's
// state out (Network::capture_slip_inputs_next).
template <bool kCapture = false>
class GenericCoupling final : public Coupling {
 public:
  GenericCoupling(const CoordinateMap& map, const Impedance& impedance, const Slot& state,
                  int state_dim, int input_dim, VecRef x_hat, VecRef u,
                  double* motion_out = nullptr, double* state_out = nullptr)
      : map_(map),
        impedance_(impedance),
        state_(state),
        state_dim_(state_dim),
        input_dim_(input_dim),
        x_hat_(x_hat),
        u_(u),
        motion_out_(motion_out),
        state_out_(state_out) {}
  void exchange(double t, const double* x_data, double tau, double* x_dot, double* u_hat) override {
    const Eigen::Map<const Vec> x(x_data, state_dim_);
    map_.motion(x, x_hat_);
    if constexpr (kCapture) {
      Eigen::Map<Vec>(motion_out_, x_hat_.size()) = x_hat_;
      Eigen::Map<Vec>(state_out_, state_.state_size) =
          x.segment(state_.state_offset, state_.state_size);
    }
    impedance_.evaluate(t, x_hat_, x.segment(state_.state_offset, state_.state_size), tau, u_,
                        Eigen::Map<Vec>(x_dot + state_.state_offset, state_.state_size));
    map_.apply(x, u_, Eigen::Map<Vec>(u_hat, input_dim_));
  }
  std::unique_ptr<Coupling> capturing(double* motion_out, double* state_out) const override {
    return std::make_unique<GenericCoupling<true>>(map_, impedance_, state_, state_dim_, input_dim_,
                                                   x_hat_, u_, motion_out, state_out);
  }

 private:
  const CoordinateMap& map_;
  const Impedance& impedance_;
  Slot state_;
  int state_dim_, input_dim_;
  VecRef x_hat_;
  VecRef u_;
  double* motion_out_;
  double* state_out_;
};

// For a direct coupling without a capturing twin: the coupling, then the map's Psi once more
// into the capture (the same bits, at the cost of a second evaluation of the map).
class CaptureAfter final : public Coupling {
 public:
  CaptureAfter(Coupling& inner, const CoordinateMap& map, const Slot& state, int state_dim,
               int motion_size, double* motion_out, double* state_out)
      : inner_(inner),
        map_(map),
        state_(state),
        state_dim_(state_dim),
        motion_size_(motion_size),
        motion_out_(motion_out),
        state_out_(state_out) {}
  void exchange(double t, const double* x_data, double tau, double* x_dot, double* u_hat) override {
    inner_.exchange(t, x_data, tau, x_dot, u_hat);
    const Eigen::Map<const Vec> x(x_data, state_dim_);
    map_.motion(x, Eigen::Map<Vec>(motion_out_, motion_size_));
    Eigen::Map<Vec>(state_out_, state_.state_size) =
        x.segment(state_.state_offset, state_.state_size);
  }

 private:
  Coupling& inner_;
  const CoordinateMap& map_;
  Slot state_;
  int state_dim_, motion_size_;
  double* motion_out_;
  double* state_out_;
};

}  // namespace

double Admittance::energy(ConstVecRef /*x*/) const {
  return std::numeric_limits<double>::quiet_NaN();
}

std::vector<bool> Admittance::velocity_slots() const {
  std::vector<bool> mask;
  for (const auto& label : state_labels()) {
    mask.push_back(label.rfind("v.", 0) == 0 || label.rfind("w.", 0) == 0 ||
                   label.rfind("omega.", 0) == 0);
  }
  return mask;
}

void Network::add_admittance(std::unique_ptr<Admittance> admittance) {
  if (finalized_) throw std::logic_error("Network: add after finalize");
  admittances_.push_back(std::move(admittance));
}

void Network::add_impedance(std::unique_ptr<Impedance> impedance,
                            std::unique_ptr<CoordinateMap> map) {
  if (finalized_) throw std::logic_error("Network: add after finalize");
  if (impedance->input_size() != map->motion_size() ||
      impedance->output_size() != map->force_size()) {
    throw std::logic_error("Network: impedance '" + impedance->name() +
                           "' does not fit its coordinate map");
  }
  impedances_.push_back(std::move(impedance));
  maps_.push_back(std::move(map));
}

void Network::finalize() {
  if (finalized_) return;
  int state = 0;
  int input = 0;
  for (const auto& a : admittances_) {
    admittance_slots_.push_back({state, a->state_size(), input, a->input_size()});
    state += a->state_size();
    input += a->input_size();
  }
  int motion = 0;
  int output = 0;
  for (const auto& i : impedances_) {
    capabilities_.push_back(capabilities_of(*i));
    if (capabilities_.back().source != nullptr) {
      sources_.push_back(static_cast<int>(capabilities_.size()) - 1);
    }
    impedance_slots_.push_back({state, i->state_size(), motion, i->input_size()});
    output_offsets_.push_back(output);
    output_sizes_.push_back(i->output_size());
    state += i->state_size();
    motion += i->input_size();
    output += i->output_size();
  }
  state_dim_ = state;
  position_slots_.assign(state_dim_, false);
  for (std::size_t j = 0; j < admittances_.size(); ++j) {
    const auto mask = admittances_[j]->velocity_slots();
    for (int k = 0; k < admittance_slots_[j].state_size; ++k) {
      position_slots_[admittance_slots_[j].state_offset + k] = !mask.at(k);
    }
  }
  zero_input_ = Vec::Zero(input);
  for (auto& m : maps_) {
    std::vector<Slot> slots;
    for (const Admittance* wanted : m->admittances()) {
      bool found = false;
      for (std::size_t j = 0; j < admittances_.size(); ++j) {
        if (admittances_[j].get() == wanted) {
          slots.push_back(admittance_slots_[j]);
          found = true;
        }
      }
      if (!found) throw std::logic_error("Network: a map refers to an unknown admittance");
    }
    m->bind(slots);
  }
  auto total_size = [](const std::vector<SignalInfo>& signals) {
    int n = 0;
    for (const auto& sig : signals) n += sig.size();
    return n;
  };
  for (const auto& a : admittances_) admittance_signal_sizes_.push_back(total_size(a->signals()));
  for (const auto& i : impedances_) impedance_signal_sizes_.push_back(total_size(i->signals()));
  signal_count_ = static_cast<int>(signal_columns().size());
  x_hat_ = Vec::Zero(motion);
  u_ = Vec::Zero(output);
  u_hat_ = Vec::Zero(input);
  scratch_dot_ = Vec::Zero(state_dim_);
  for (std::size_t i = 0; i < impedances_.size(); ++i) {
    const Slot& s = impedance_slots_[i];
    auto coupling = maps_[i]->direct_coupling(*impedances_[i], s);
    if (!coupling) {
      coupling =
          std::make_unique<GenericCoupling<>>(*maps_[i], *impedances_[i], s, state_dim_, input,
                                              x_hat_.segment(s.input_offset, s.input_size),
                                              u_.segment(output_offsets_[i], output_sizes_[i]));
    }
    couplings_.push_back(std::move(coupling));
  }
  prepare_capture();
  for (std::size_t j = 0; j < admittances_.size(); ++j) {
    admittance_calls_.push_back({admittances_[j].get(), admittance_slots_[j].state_offset,
                                 admittance_slots_[j].input_offset});
  }
  coupling_count_ = static_cast<int>(couplings_.size());
  admittance_count_ = static_cast<int>(admittance_calls_.size());
  input_count_ = input;
  finalized_ = true;
}

Vec Network::initial_state() const {
  Vec x = Vec::Zero(state_dim_);
  for (std::size_t j = 0; j < admittances_.size(); ++j) {
    const Slot& s = admittance_slots_[j];
    admittances_[j]->initial_state(x.segment(s.state_offset, s.state_size));
  }
  for (std::size_t i = 0; i < impedances_.size(); ++i) {
    const Slot& s = impedance_slots_[i];
    impedances_[i]->initial_state(x.segment(s.state_offset, s.state_size));
  }
  return x;
}

std::vector<LayoutEntry> Network::layout() const {
  std::vector<LayoutEntry> entries;
  for (std::size_t j = 0; j < admittances_.size(); ++j) {
    const auto& a = *admittances_[j];
    entries.push_back({a.name(), std::string(a.type()), admittance_slots_[j].state_offset,
                       a.state_size(), a.state_labels()});
  }
  for (std::size_t i = 0; i < impedances_.size(); ++i) {
    const auto& m = *impedances_[i];
    entries.push_back({m.name(), std::string(m.type()), impedance_slots_[i].state_offset,
                       m.state_size(), m.state_labels()});
  }
  return entries;
}

template <typename F>
void Network::for_each_index(const std::vector<int>* listed, std::size_t count, F f) {
  if (listed != nullptr) {
    for (int i : *listed) f(static_cast<std::size_t>(i));
    return;
  }
  for (std::size_t i = 0; i < count; ++i) f(i);
}

void Network::evaluate_impedances(double t, ConstVecRef x, double tau, VecRef x_dot,
                                  const Vec* friction_reference, const Island* part) {
  // (13d) Psi, (22) impedances, (13f) Phi.
  if (part == nullptr) {
    u_hat_.setZero();
  } else {
    for (int j : part->admittances) {
      const Slot& s = admittance_slots_[static_cast<std::size_t>(j)];
      u_hat_.segment(s.input_offset, s.input_size).setZero();
    }
  }
  for_each_index(part ? &part->impedances : nullptr, impedances_.size(), [&](std::size_t i) {
    const Slot& s = impedance_slots_[i];
    const Impedance& imp = *impedances_[i];
    auto x_hat = x_hat_.segment(s.input_offset, s.input_size);
    auto u = u_.segment(output_offsets_[i], output_sizes_[i]);
    auto y_dot = x_dot.segment(s.state_offset, s.state_size);
    const ClampedFriction* friction = capabilities_[i].friction;
    if (friction_reference != nullptr && friction != nullptr) {
      const Vec& reference = *friction_reference;
      Vec u_ref(output_sizes_[i]), y_dot_ref(s.state_size);
      maps_[i]->motion(reference, x_hat);
      imp.evaluate(t, x_hat, reference.segment(s.state_offset, s.state_size), tau, u_ref,
                   y_dot_ref);
      maps_[i]->motion(x, x_hat);
      friction->evaluate_friction_held(t, x_hat, x.segment(s.state_offset, s.state_size), tau,
                                       u_ref, y_dot_ref, u, y_dot);
    } else {
      maps_[i]->motion(x, x_hat);
      imp.evaluate(t, x_hat, x.segment(s.state_offset, s.state_size), tau, u, y_dot);
    }
    maps_[i]->apply(x, u, u_hat_);
  });
}

void Network::evaluate_admittances(const double* x, double* x_dot) {
  // (13g) admittances. Inline into derivative_at(): one call less on every stage.
  const double* u_hat = u_hat_.data();
  const AdmittanceCall* const end = admittance_calls_.data() + admittance_count_;
  for (const AdmittanceCall* call = admittance_calls_.data(); call != end; ++call) {
    call->admittance->derivative_at(x + call->state_offset, u_hat + call->input_offset,
                                    x_dot + call->state_offset);
  }
}

void Network::derivative_at(double t, const double* x, double tau, double* x_dot) {
  // (13d) Psi, (22) impedances, (13f) Phi. The capturing couplings serve one call only.
  Coupling* const* couplings = active_;
  active_ = plain_.data();
  double* u_hat = u_hat_.data();
  for (int k = 0; k < input_count_; ++k) u_hat[k] = 0.0;
  Coupling* const* const end = couplings + coupling_count_;
  for (; couplings != end; ++couplings) (*couplings)->exchange(t, x, tau, x_dot, u_hat);
  evaluate_admittances(x, x_dot);
}

void Network::derivative_part(double t, const double* x, double tau, double* x_dot,
                              const Island& part) {
  double* u_hat = u_hat_.data();
  for (int j : part.admittances) {
    const Slot& s = admittance_slots_[static_cast<std::size_t>(j)];
    for (int k = 0; k < s.input_size; ++k) u_hat[s.input_offset + k] = 0.0;
  }
  for (int i : part.impedances) {
    plain_[static_cast<std::size_t>(i)]->exchange(t, x, tau, x_dot, u_hat);
  }
  for (int j : part.admittances) {
    const AdmittanceCall& call = admittance_calls_[static_cast<std::size_t>(j)];
    call.admittance->derivative_at(x + call.state_offset, u_hat + call.input_offset,
                                   x_dot + call.state_offset);
  }
}

void Network::prepare_capture() {
  int size = 0;
  for (std::size_t i = 0; i < impedances_.size(); ++i) {
    const bool slips = capabilities_[i].slip != nullptr;
    capture_offsets_.push_back(slips ? size : -1);
    if (slips) size += impedance_slots_[i].input_size + impedance_slots_[i].state_size;
  }
  captured_ = Vec::Zero(size);
  for (std::size_t i = 0; i < impedances_.size(); ++i) {
    Coupling* plain = couplings_[i].get();
    plain_.push_back(plain);
    if (capture_offsets_[i] < 0) {
      capturing_.push_back(plain);
      continue;
    }
    const Slot& s = impedance_slots_[i];
    double* motion = captured_.data() + capture_offsets_[i];
    double* state = motion + s.input_size;
    std::unique_ptr<Coupling> twin = plain->capturing(motion, state);
    if (!twin) {
      twin = std::make_unique<CaptureAfter>(*plain, *maps_[i], s, state_dim_, s.input_size, motion,
                                            state);
    }
    capturing_.push_back(twin.get());
    capturing_owned_.push_back(std::move(twin));
  }
  active_ = plain_.data();
}

ConstVecRef Network::captured_input(int impedance) const {
  return captured_.segment(capture_offsets_.at(impedance), impedance_slots_[impedance].input_size);
}

ConstVecRef Network::captured_state(int impedance) const {
  const Slot& s = impedance_slots_[impedance];
  return captured_.segment(capture_offsets_.at(impedance) + s.input_size, s.state_size);
}

void Network::derivative_friction_held(double t, ConstVecRef x, double tau, VecRef x_dot,
                                       const Vec& reference, const Island* part) {
  evaluate_impedances(t, x, tau, x_dot, &reference, part);
  if (part == nullptr) {
    evaluate_admittances(x.data(), x_dot.data());
    return;
  }
  for (int j : part->admittances) {
    const AdmittanceCall& call = admittance_calls_[static_cast<std::size_t>(j)];
    call.admittance->derivative_at(x.data() + call.state_offset, u_hat_.data() + call.input_offset,
                                   x_dot.data() + call.state_offset);
  }
}

double Network::friction_cap_energy(ConstVecRef x, const Island* part) {
  double total = 0.0;
  for_each_index(part ? &part->impedances : nullptr, impedances_.size(), [&](std::size_t i) {
    const ClampedFriction* friction = capabilities_[i].friction;
    if (friction == nullptr) return;
    const Slot& s = impedance_slots_[i];
    auto x_hat = x_hat_.segment(s.input_offset, s.input_size);
    maps_[i]->motion(x, x_hat);
    total += friction->friction_cap_energy(x_hat);
  });
  return total;
}

void Network::kinematics(ConstVecRef x, VecRef x_dot, const Island* part) const {
  for_each_index(part ? &part->admittances : nullptr, admittances_.size(), [&](std::size_t j) {
    const Slot& s = admittance_slots_[j];
    admittances_[j]->derivative(x.segment(s.state_offset, s.state_size),
                                zero_input_.segment(s.input_offset, s.input_size),
                                x_dot.segment(s.state_offset, s.state_size));
  });
}

void Network::project(VecRef x, const Island* part) const {
  for_each_index(part ? &part->admittances : nullptr, admittances_.size(), [&](std::size_t j) {
    const Slot& s = admittance_slots_[j];
    admittances_[j]->project(x.segment(s.state_offset, s.state_size));
  });
}

void Network::solve_kinematics(const Vec& start, Vec& iterate, double h,
                               const Island* part) const {
  for_each_index(part ? &part->admittances : nullptr, admittances_.size(), [&](std::size_t j) {
    const Slot& s = admittance_slots_[j];
    admittances_[j]->solve_kinematics(start.data() + s.state_offset,
                                      iterate.data() + s.state_offset, h);
  });
}

std::vector<std::string> Network::signal_columns() const {
  std::vector<std::string> names;
  for (const auto& a : admittances_) {
    auto c = column_names(a->name(), a->signals());
    names.insert(names.end(), c.begin(), c.end());
  }
  for (const auto& i : impedances_) {
    auto c = column_names(i->name(), i->signals());
    names.insert(names.end(), c.begin(), c.end());
  }
  return names;
}

std::vector<bool> Network::wrapped_columns() const {
  std::vector<bool> wrapped;
  auto add = [&](const std::vector<SignalInfo>& signals) {
    for (const auto& sig : signals) wrapped.insert(wrapped.end(), sig.size(), sig.unwrap);
  };
  for (const auto& a : admittances_) add(a->signals());
  for (const auto& i : impedances_) add(i->signals());
  return wrapped;
}

void Network::write_signals(double t, ConstVecRef x, double tau, VecRef row) {
  evaluate_impedances(t, x, tau, scratch_dot_);
  int col = 0;
  for (std::size_t j = 0; j < admittances_.size(); ++j) {
    const Slot& s = admittance_slots_[j];
    const int n = admittance_signal_sizes_[j];
    admittances_[j]->write_signals(x.segment(s.state_offset, s.state_size), row.segment(col, n));
    col += n;
  }
  for (std::size_t i = 0; i < impedances_.size(); ++i) {
    const Slot& s = impedance_slots_[i];
    const int n = impedance_signal_sizes_[i];
    impedances_[i]->write_signals(x_hat_.segment(s.input_offset, s.input_size),
                                  x.segment(s.state_offset, s.state_size),
                                  u_.segment(output_offsets_[i], impedances_[i]->output_size()),
                                  row.segment(col, n));
    col += n;
  }
}

Vec3 Network::slip_velocity(int impedance, ConstVecRef x) {
  const Slot& s = impedance_slots_[impedance];
  auto x_hat = x_hat_.segment(s.input_offset, s.input_size);
  maps_[impedance]->motion(x, x_hat);
  return capabilities_[impedance].slip->slip_velocity(x_hat);
}

ConstVecRef Network::impedance_input(int impedance, ConstVecRef x) {
  const Slot& s = impedance_slots_[impedance];
  auto x_hat = x_hat_.segment(s.input_offset, s.input_size);
  maps_[impedance]->motion(x, x_hat);
  return x_hat;
}

std::size_t Network::regime_signature(ConstVecRef x, double tau, const Island* part) {
  std::size_t signature = 0;
  for_each_index(part ? &part->impedances : nullptr, impedances_.size(), [&](std::size_t i) {
    int r = 0;  // smooth elements have one piece
    if (const PiecewiseLaw* law = capabilities_[i].law) {
      const Slot& s = impedance_slots_[i];
      auto x_hat = x_hat_.segment(s.input_offset, s.input_size);
      maps_[i]->motion(x, x_hat);
      r = law->regime(x_hat, x.segment(s.state_offset, s.state_size), tau);
    }
    signature = signature * 31 + static_cast<std::size_t>(r + 1);
  });
  return signature;
}

bool Network::has_sources() const { return !sources_.empty(); }

bool Network::has_feedback_sources() const {
  for (const int i : sources_) {
    if (capabilities_[i].source->reads_state()) return true;
  }
  return false;
}

double Network::source_power(double t, ConstVecRef x, bool driven_only) {
  double power = 0.0;
  for (const int i : sources_) {
    if (driven_only && capabilities_[i].source->reads_state()) continue;
    const Slot& s = impedance_slots_[i];
    auto x_hat = x_hat_.segment(s.input_offset, s.input_size);
    auto u = u_.segment(output_offsets_[i], impedances_[i]->output_size());
    auto y_dot = scratch_dot_.segment(s.state_offset, s.state_size);
    maps_[i]->motion(x, x_hat);
    impedances_[i]->evaluate(t, x_hat, x.segment(s.state_offset, s.state_size), 0.0, u, y_dot);
    power += capabilities_[i].source->power_in(x_hat, u);
  }
  return power;
}

double Network::energy(ConstVecRef x) {
  double total = 0.0;
  for (std::size_t j = 0; j < admittances_.size(); ++j) {
    const Slot& s = admittance_slots_[j];
    total += admittances_[j]->energy(x.segment(s.state_offset, s.state_size));
  }
  return add_stored_energy(x, total);
}

double Network::add_stored_energy(ConstVecRef x, double total) {
  for (std::size_t i = 0; i < impedances_.size(); ++i) {
    const EnergyStore* store = capabilities_[i].energy;
    if (store == nullptr) continue;  // holds none
    const Slot& s = impedance_slots_[i];
    auto x_hat = x_hat_.segment(s.input_offset, s.input_size);
    maps_[i]->motion(x, x_hat);
    total += store->stored_energy(x_hat, x.segment(s.state_offset, s.state_size));
  }
  return total;
}

const Admittance* Network::find_admittance(const std::string& name) const {
  for (const auto& a : admittances_) {
    if (a->name() == name) return a.get();
  }
  return nullptr;
}

}  // namespace stiction::core
