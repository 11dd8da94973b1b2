#include "core/spectrum.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>

namespace stiction::core {

std::optional<Eigen::VectorXcd> eigenvalues(const Eigen::MatrixXd& a) {
  const Eigen::EigenSolver<Eigen::MatrixXd> real(a, false);
  if (real.info() == Eigen::Success) return Eigen::VectorXcd(real.eigenvalues());
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> complex(a.cast<std::complex<double>>(),
                                                            false);
  if (complex.info() == Eigen::Success) return Eigen::VectorXcd(complex.eigenvalues());
  return std::nullopt;
}

std::optional<double> spectral_radius(const Eigen::MatrixXd& phi) {
  if (!phi.allFinite()) return INFINITY;
  const auto mu = eigenvalues(phi);
  if (!mu) return std::nullopt;
  return mu->cwiseAbs().maxCoeff();
}

}  // namespace stiction::core
