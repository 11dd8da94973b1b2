// Eigenvalues and spectral radii of the dense step maps the stability analysis builds
// (core/stability.cpp), with every solver failure seen instead of read as a number.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace stiction::core {

// The diagonal blocks of a's Frobenius normal form: the strongly connected components of the
// graph with an edge i -> j wherever a(i, j) != 0 (NaN included), each as its indices in
// ascending order. Permuted block by block, a is block triangular, so its eigenvalues are
// those of its diagonal blocks a(block, block) together: exactly, not approximately. A step
// map is seldom irreducible: the entries that nothing feeds back on (a free body's position
// along a plane, a quaternion its spin drives, a contact's friction state that only the
// normal force moves) each make a block of their own, and a sphere's 15 states on a floor
// fall into blocks of 1, 2, 3 and 6 states (measured on the 1000-sphere scene).
std::vector<std::vector<int>> irreducible_blocks(const Eigen::MatrixXd& a);

// The eigenvalues of a, or none where no solver converges, block by block
// (irreducible_blocks: a block of one entry is its eigenvalue; a sphere's 15 x 15 step map
// costs a 6 x 6 problem and a few 2 x 2 or 3 x 3 ones instead of one 15 x 15), in the order
// of the blocks' first index.
// Eigen's real Schur iteration (EigenSolver) fails now and then on the badly scaled step
// maps of a stuck stiff contact (entries from 1e-7 to 600), and its eigenvalues are then
// zeros or garbage unless info() is read: a rolling ball's stuck step map, radius 1.0, was
// read as 4630 and called chatter at 0.006 s. The complex Schur iteration is tried next.
std::optional<Eigen::VectorXcd> eigenvalues(const Eigen::MatrixXd& a);

// The largest |eigenvalue| of phi: infinite where phi is not finite (a step map that
// overflows grows), none where no solver converges (no answer, as on a switching surface).
std::optional<double> spectral_radius(const Eigen::MatrixXd& phi);

// The spectral radius of phi where it exceeds `threshold`; where it does not, a value at most
// threshold (a bound, when one is cheaper than the eigenvalues: the norms of a block's powers,
// accepted up to threshold - kRadiusMargin). Infinite where phi is not finite,
// none where no solver converges. For a search that only asks whether a step map grows
// faster than a threshold (core/stability.cpp): most of the blocks it meets are
// bounded well below it, and their eigenvalues are never needed.
inline constexpr double kRadiusMargin = 0.01;
std::optional<double> spectral_radius_beyond(const Eigen::MatrixXd& phi, double threshold);

}  // namespace stiction::core
