// Eigenvalues and spectral radii of the dense step maps the stability analysis builds
// (core/stability.cpp), with every solver failure seen instead of read as a number.
#pragma once

#include <Eigen/Core>
#include <optional>

namespace stiction::core {

// The eigenvalues of a, or none where no solver converges. Eigen's real Schur iteration
// (EigenSolver) fails now and then on the badly scaled step maps of a stuck stiff contact
// (entries from 1e-7 to 600), and its eigenvalues are then zeros or garbage unless info()
// is read: a rolling ball's stuck step map, radius 1.0, was read as 4630 and called
// chatter at 0.006 s. The complex Schur iteration is tried next.
std::optional<Eigen::VectorXcd> eigenvalues(const Eigen::MatrixXd& a);

// The largest |eigenvalue| of phi: infinite where phi is not finite (a step map that
// overflows grows), none where no solver converges (no answer, as on a switching surface).
std::optional<double> spectral_radius(const Eigen::MatrixXd& phi);

}  // namespace stiction::core
