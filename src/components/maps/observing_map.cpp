#include "components/maps/observing_map.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/admittance.hpp"
#include "core/impedance.hpp"

namespace stiction::components {

namespace {

int width(const std::vector<core::SignalInfo>& signals) {
  int n = 0;
  for (const auto& sig : signals) n += sig.size();
  return n;
}

}  // namespace

ObservingMap::ObservingMap(std::unique_ptr<core::CoordinateMap> inner,
                           std::vector<Observed> observed)
    : inner_(std::move(inner)), observed_(std::move(observed)) {
  inner_admittances_ = static_cast<int>(inner_->admittances().size());
  for (const Observed& o : observed_) {
    if ((o.admittance == nullptr) == (o.impedance == nullptr) ||
        (o.impedance != nullptr && o.map == nullptr)) {
      throw std::invalid_argument(
          "ObservingMap: observe an admittance or an impedance with its map");
    }
    const int n = o.admittance ? width(o.admittance->signals()) : width(o.impedance->signals());
    if (o.entry < 0 || o.entry >= n)
      throw std::invalid_argument("ObservingMap: no such signal entry");
    if (o.admittance) {
      auto it = std::find_if(bodies_.begin(), bodies_.end(),
                             [&](const BodySource& s) { return s.admittance == o.admittance; });
      if (it == bodies_.end()) {
        bodies_.push_back({o.admittance, {}, core::Vec::Zero(n)});
        it = bodies_.end() - 1;
      }
      source_of_.push_back(static_cast<int>(it - bodies_.begin()));
      raw_of_.push_back(body_values_++);
    } else {
      auto it = std::find_if(elements_.begin(), elements_.end(),
                             [&](const ElementSource& s) { return s.impedance == o.impedance; });
      if (it == elements_.end()) {
        const core::Impedance& imp = *o.impedance;
        if (o.map->motion_size() != imp.input_size() || o.map->force_size() != imp.output_size())
          throw std::invalid_argument("ObservingMap: an impedance does not fit its map");
        elements_.push_back({&imp, o.map, 0, -1, core::Vec::Zero(imp.output_size()),
                             core::Vec::Zero(imp.state_size()), core::Vec::Zero(n)});
        it = elements_.end() - 1;
      }
      source_of_.push_back(static_cast<int>(it - elements_.begin()));
      raw_of_.push_back(-1);
    }
  }
  raw_size_ = body_values_;
  for (ElementSource& e : elements_) {
    e.raw_offset = raw_size_;
    raw_size_ += e.impedance->input_size() + e.impedance->state_size();
  }
  values_ = core::Vec::Zero(static_cast<int>(observed_.size()));
}

std::vector<const core::Admittance*> ObservingMap::admittances() const {
  std::vector<const core::Admittance*> all = inner_->admittances();
  for (const BodySource& s : bodies_) all.push_back(s.admittance);
  return all;
}

void ObservingMap::bind(const std::vector<core::Slot>& slots) {
  inner_->bind(std::vector<core::Slot>(slots.begin(), slots.begin() + inner_admittances_));
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    bodies_[i].slot = slots.at(inner_admittances_ + i);
}

void ObservingMap::locate(const core::Network& network) {
  const auto& all = network.impedances();
  for (ElementSource& e : elements_) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const auto& p) { return p.get() == e.impedance; });
    if (it == all.end())
      throw std::logic_error("ObservingMap: observed impedance not in the network");
    e.state_offset = network.impedance_slot(static_cast<int>(it - all.begin())).state_offset;
  }
}

void ObservingMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const int n = inner_->motion_size();
  inner_->motion(x, x_hat.head(n));
  for (const BodySource& s : bodies_) {
    s.admittance->write_signals(x.segment(s.slot.state_offset, s.slot.state_size), s.signals);
  }
  for (std::size_t i = 0; i < observed_.size(); ++i) {
    if (raw_of_[i] >= 0) x_hat[n + raw_of_[i]] = bodies_[source_of_[i]].signals[observed_[i].entry];
  }
  for (const ElementSource& e : elements_) {
    if (e.state_offset < 0) throw std::logic_error("ObservingMap: motion() before locate()");
    const int in = e.impedance->input_size();
    const int size = e.impedance->state_size();
    e.map->motion(x, x_hat.segment(n + e.raw_offset, in));
    x_hat.segment(n + e.raw_offset + in, size) = x.segment(e.state_offset, size);
  }
}

const double* ObservingMap::values(double t, double tau, const double* raw) const {
  for (const ElementSource& e : elements_) {
    const int in = e.impedance->input_size();
    const Eigen::Map<const core::Vec> x_hat(raw + e.raw_offset, in);
    const Eigen::Map<const core::Vec> y(raw + e.raw_offset + in, e.impedance->state_size());
    e.impedance->evaluate(t, x_hat, y, tau, e.u, e.y_dot);
    e.impedance->write_signals(x_hat, y, e.u, e.signals);
  }
  for (std::size_t i = 0; i < observed_.size(); ++i) {
    values_[static_cast<int>(i)] =
        raw_of_[i] >= 0 ? raw[raw_of_[i]] : elements_[source_of_[i]].signals[observed_[i].entry];
  }
  return values_.data();
}

}  // namespace stiction::components
