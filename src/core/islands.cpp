#include "core/islands.hpp"

#include <algorithm>

#include "core/network.hpp"

namespace stiction::core {

namespace {

// Union-find over state entries, path halving.
class Partition {
 public:
  explicit Partition(int size) : parent_(static_cast<std::size_t>(size)) {
    for (std::size_t i = 0; i < parent_.size(); ++i) parent_[i] = static_cast<int>(i);
  }
  int root(int i) {
    while (parent_[static_cast<std::size_t>(i)] != i) {
      auto& p = parent_[static_cast<std::size_t>(i)];
      p = parent_[static_cast<std::size_t>(p)];
      i = p;
    }
    return i;
  }
  void join(int a, int b) { parent_[static_cast<std::size_t>(root(a))] = root(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace

std::vector<Island> find_islands(const Network& network, const std::vector<char>* detached) {
  const auto& admittances = network.admittances();
  const int n_adm = static_cast<int>(admittances.size());
  const int n_imp = static_cast<int>(network.impedances().size());
  Partition partition(network.state_dim());
  const auto join_slot = [&](const Slot& s, int anchor) {
    for (int k = 0; k < s.state_size; ++k) partition.join(s.state_offset + k, anchor);
  };
  for (int j = 0; j < n_adm; ++j) {
    const Slot s = network.admittance_slot(j);
    if (s.state_size > 0) join_slot(s, s.state_offset);
  }
  // Which admittance each map names (maps hold pointers; a scene has few admittances per
  // map, so one lookup table instead of a search per pointer).
  std::vector<std::pair<const Admittance*, int>> index;
  index.reserve(admittances.size());
  for (int j = 0; j < n_adm; ++j)
    index.emplace_back(admittances[static_cast<std::size_t>(j)].get(), j);
  std::sort(index.begin(), index.end());
  const auto find = [&](const Admittance* a) {
    const auto it = std::lower_bound(index.begin(), index.end(), std::make_pair(a, -1));
    return it != index.end() && it->first == a ? it->second : -1;
  };
  // anchor[i]: a state entry of impedance i's island, -1 if it touches no state.
  std::vector<int> anchor(static_cast<std::size_t>(n_imp), -1);
  std::vector<std::vector<int>> moved(static_cast<std::size_t>(n_imp));
  for (int i = 0; i < n_imp; ++i) {
    int& a = anchor[static_cast<std::size_t>(i)];
    const bool alone = detached != nullptr && (*detached)[static_cast<std::size_t>(i)] != 0;
    for (const Admittance* body : network.map_of(i).admittances()) {
      if (alone) break;
      const int j = find(body);
      if (j < 0) continue;
      moved[static_cast<std::size_t>(i)].push_back(j);
      const Slot s = network.admittance_slot(j);
      if (s.state_size == 0) continue;
      if (a < 0) a = s.state_offset;
      partition.join(s.state_offset, a);
    }
    const Slot own = network.impedance_slot(i);
    if (own.state_size > 0) {
      if (a < 0) a = own.state_offset;
      join_slot(own, a);
    }
  }
  std::vector<Island> islands;
  std::vector<int> island_of_root(static_cast<std::size_t>(network.state_dim()), -1);
  const auto island_at = [&](int entry) -> Island& {
    int& k = island_of_root[static_cast<std::size_t>(partition.root(entry))];
    if (k < 0) {
      k = static_cast<int>(islands.size());
      islands.emplace_back();
    }
    return islands[static_cast<std::size_t>(k)];
  };
  for (int e = 0; e < network.state_dim(); ++e) island_at(e).states.push_back(e);
  for (int j = 0; j < n_adm; ++j) {
    const Slot s = network.admittance_slot(j);
    if (s.state_size > 0) island_at(s.state_offset).admittances.push_back(j);
  }
  for (int i = 0; i < n_imp; ++i) {
    const int a = anchor[static_cast<std::size_t>(i)];
    if (a < 0) continue;
    Island& island = island_at(a);
    island.impedances.push_back(i);
    // A stateless admittance an element moves (a fixed frame) goes with it: its forces
    // are part of the island's evaluation.
    for (int j : moved[static_cast<std::size_t>(i)]) {
      if (network.admittance_slot(j).state_size == 0 &&
          std::find(island.admittances.begin(), island.admittances.end(), j) ==
              island.admittances.end()) {
        island.admittances.push_back(j);
      }
    }
  }
  for (Island& island : islands) std::sort(island.admittances.begin(), island.admittances.end());
  return islands;
}

}  // namespace stiction::core
