#include "components/maps/observing_map.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/admittance.hpp"

namespace stiction::components {

ObservingMap::ObservingMap(std::unique_ptr<core::CoordinateMap> inner,
                           std::vector<Observed> observed)
    : inner_(std::move(inner)), observed_(std::move(observed)) {
  inner_admittances_ = static_cast<int>(inner_->admittances().size());
  for (const Observed& o : observed_) {
    auto it = std::find_if(sources_.begin(), sources_.end(),
                           [&](const Source& s) { return s.admittance == o.admittance; });
    if (it == sources_.end()) {
      int width = 0;
      for (const auto& sig : o.admittance->signals()) width += sig.size();
      if (o.entry < 0 || o.entry >= width)
        throw std::invalid_argument("ObservingMap: no such signal entry");
      sources_.push_back({o.admittance, {}, core::Vec::Zero(width)});
      it = sources_.end() - 1;
    }
    source_of_.push_back(static_cast<int>(it - sources_.begin()));
  }
}

std::vector<const core::Admittance*> ObservingMap::admittances() const {
  std::vector<const core::Admittance*> all = inner_->admittances();
  for (const Source& s : sources_) all.push_back(s.admittance);
  return all;
}

void ObservingMap::bind(const std::vector<core::Slot>& slots) {
  inner_->bind(std::vector<core::Slot>(slots.begin(), slots.begin() + inner_admittances_));
  for (std::size_t i = 0; i < sources_.size(); ++i)
    sources_[i].slot = slots.at(inner_admittances_ + i);
}

void ObservingMap::motion(core::ConstVecRef x, core::VecRef x_hat) const {
  const int n = inner_->motion_size();
  inner_->motion(x, x_hat.head(n));
  for (const Source& s : sources_) {
    s.admittance->write_signals(x.segment(s.slot.state_offset, s.slot.state_size), s.signals);
  }
  for (std::size_t i = 0; i < observed_.size(); ++i) {
    x_hat[n + static_cast<int>(i)] = sources_[source_of_[i]].signals[observed_[i].entry];
  }
}

}  // namespace stiction::components
