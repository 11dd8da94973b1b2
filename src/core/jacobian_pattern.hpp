// The structure of an island's Jacobian dF/dx from the network's wiring, for compressed
// finite differences (Curtis, Powell & Reid, 1974) and a sparse factorization (issue 36
// item 3).
//
// An admittance's rate depends on its own state and its input; its input is the sum of the
// forces of the impedances whose maps move it; an impedance's force and state rate depend on
// the admittances its map moves and its own state (core/coupling.hpp). So the state entries
// an element touches (the admittances its map moves, its own state) form a clique: each can
// change the rate of each. No other entry can: a body's state changes only the rates of the
// bodies it shares an element with, and theirs to the bit stay as they were.
//
// Blocks are the state slices of the island's admittances and impedances. Two blocks whose
// row sets (the blocks they can change) do not meet are perturbed in one evaluation: their
// differences land in disjoint rows. A tower of boxes (each touching the ones next to it)
// needs about three evaluations per unknown of a box instead of one per unknown of the tower;
// a pile with every pair in contact is one clique and gains nothing. Since an evaluation
// changes no row outside its perturbed blocks' row sets by even a bit, the compressed
// matrix equals the one-column-at-a-time matrix to the bit.
//
// Stars: a group's rows change only through the elements whose clique holds a perturbed
// block. In a large island those are few (a body of a pile of 64 with a contact between
// every two: 63 of 2016 elements), so the group is evaluated on its star (those elements and
// the bodies they move) twice, unperturbed and perturbed, instead of on the whole island
// once. A perturbed body's input is whole in its star (every element on it is there), so
// its rows are the island's to the bit; a neighbour's input lacks the forces of the
// elements outside, which moves its rate by the same amount in both evaluations when the
// rate is affine in the input (Admittance::affine_in_input): its rows differ from the
// island's by rounding only. A star is used when the island has at least kStarElements
// elements (impedances: a box's contact is one per corner) and the star at most kStarShare
// of its state entries (two evaluations of it then cost at most 80% of the island's one, by
// the measure evaluations are counted in; an arm's star holds the whole arm, so a star of
// one joint's element is not cheaper), so small islands (every bundled scene) keep their
// matrices to the bit.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/islands.hpp"

namespace stiction::core {

class Network;

struct JacobianPattern {
  // Columns (indices into the island's solved entries) perturbed together, one evaluation
  // each.
  std::vector<std::vector<int>> groups;
  // Per group: the index of its star in `stars`, or -1 (the whole island is evaluated).
  std::vector<int> group_star;
  std::vector<Island> stars;
  // Per column: the rows (indices into the solved entries, ascending) its difference can
  // change. Always holds the column's own row.
  std::vector<std::vector<int>> rows;
  // Entries of the pattern: the sum of the rows' sizes.
  Eigen::Index nonzeros() const;
};

// solved: the island's solved state entries (ascending; ImplicitEulerStepper's
// IslandSolve::solved).
// use_stars: whether groups may be evaluated on their stars (false: the whole island).
JacobianPattern jacobian_pattern(const Network& network, const Island& island,
                                 const std::vector<int>& solved, bool use_stars = true);

// The thresholds for stars (above).
inline constexpr std::size_t kStarElements = 32;
inline constexpr double kStarShare = 0.4;

}  // namespace stiction::core
