// A coordinate map that also observes: x_hat = [inner map's x_hat, observed values], where
// each observed value is one signal entry of an admittance (a CSV column such as
// "arm.theta.0") read from the state the network evaluates, i.e. from the integrator's
// stage state. Phi is the inner map's: the observed admittances receive no force.
// This is how an element's law can depend on the state of other components (feedback)
// without the core knowing: the network hands every map the whole stage state anyway.
#pragma once

#include <memory>
#include <vector>

#include "core/coordinate_map.hpp"

namespace stiction::components {

class ObservingMap final : public core::CoordinateMap {
 public:
  struct Observed {
    const core::Admittance* admittance = nullptr;
    int entry = 0;  // index into the admittance's signal entries (its CSV columns, in order)
  };
  ObservingMap(std::unique_ptr<core::CoordinateMap> inner, std::vector<Observed> observed);
  int motion_size() const override {
    return inner_->motion_size() + static_cast<int>(observed_.size());
  }
  int force_size() const override { return inner_->force_size(); }
  std::vector<const core::Admittance*> admittances() const override;
  void bind(const std::vector<core::Slot>& slots) override;
  void motion(core::ConstVecRef x, core::VecRef x_hat) const override;
  void apply(core::ConstVecRef x, core::ConstVecRef u, core::VecRef u_hat) const override {
    inner_->apply(x, u, u_hat);
  }
  const core::CoordinateMap& inner() const { return *inner_; }
  const std::vector<Observed>& observed() const { return observed_; }

 private:
  struct Source {  // one observed admittance
    const core::Admittance* admittance;
    core::Slot slot;
    mutable core::Vec signals;  // scratch for its signal row, sized once
  };
  std::unique_ptr<core::CoordinateMap> inner_;
  std::vector<Observed> observed_;
  int inner_admittances_ = 0;
  std::vector<Source> sources_;
  std::vector<int> source_of_;  // per observed value: index into sources_
};

}  // namespace stiction::components
