// Normalization that cannot overflow or underflow: Eigen's normalized() squares the entries,
// so [1e308, 1e308, 1e308, 1e308] has norm inf and becomes (0, 0, 0, 0), and [1e-200, 0, 0]
// has norm 0 (issue 25: an orientation of huge components ran as the zero quaternion with
// exit 0). Dividing by the largest magnitude first keeps every entry in [-1, 1]; the result
// is then checked to be finite and of unit length.
#pragma once

#include <cmath>
#include <optional>

#include <Eigen/Core>

namespace stiction::core {

// v / |v|, or nothing when v is zero or has an entry that is not finite.
template <typename Derived>
std::optional<typename Derived::PlainObject> safe_normalized(const Eigen::MatrixBase<Derived>& v) {
  using Plain = typename Derived::PlainObject;
  if (!v.allFinite()) return std::nullopt;
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0.0)) return std::nullopt;
  Plain u = v / largest;
  u /= u.norm();
  if (!u.allFinite() || !(std::abs(u.norm() - 1.0) < 1e-12)) return std::nullopt;
  return u;
}

}  // namespace stiction::core
