// Islands of a network: the groups of bodies that no element couples (MuJoCo's constraint
// islands). An impedance belongs to the island of the admittances its map moves, and joins
// them into one; its own state goes with them. Separate islands can be stepped by separate
// Newton iterations, matrices and step splits: what one island does (a sphere that switches
// from slip to roll) costs the others nothing.
//
// Islands follow the network's structure, except for the elements named `detached`: a
// contact between two bodies that are apart (NormalContact::gap) exerts no force and its
// state evolves on its own, so it joins nothing and forms an island of its own state. The
// implicit step detaches the contacts a step cannot close and recomputes the islands when
// that set changes.
#pragma once

#include <vector>

namespace stiction::core {

class Network;

struct Island {
  std::vector<int> admittances;  // indices into Network::admittances(), ascending
  std::vector<int> impedances;   // indices into Network::impedances(), ascending
  std::vector<int> states;       // the state entries of both, ascending
};

// Every admittance or impedance that has state entries, or whose map moves an admittance
// that has, is in exactly one island; impedances that touch no state at all (nothing to
// step) are in none. Islands come in the order of their first state entry.
// detached: one flag per impedance (or nullptr: none).
std::vector<Island> find_islands(const Network& network,
                                 const std::vector<char>* detached = nullptr);

}  // namespace stiction::core
