// A mark for exceptions thrown from inside a component's evaluation that are the model's
// fault, not the integrator's: a user's expression that gives a non-finite value at finite
// inputs (scene/expression.hpp). core::simulate turns the runtime errors of a step into an
// instability (a step that failed to converge); one carrying this mark passes through
// instead, so that the run is reported as bad input at the expression, not as an
// instability with a smaller step to try (issue 25).
#pragma once

namespace stiction::core {

class ModelFault {
 public:
  virtual ~ModelFault() = default;
};

}  // namespace stiction::core
