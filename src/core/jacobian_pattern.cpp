#include "core/jacobian_pattern.hpp"

#include <algorithm>
#include <utility>

#include "core/islands.hpp"
#include "core/network.hpp"

namespace stiction::core {

Eigen::Index JacobianPattern::nonzeros() const {
  Eigen::Index n = 0;
  for (const auto& r : rows) n += static_cast<Eigen::Index>(r.size());
  return n;
}

namespace {

struct Block {
  int offset = 0;
  int size = 0;
  std::vector<int> columns;  // its solved entries, as indices into `solved`
  std::vector<int> reach;    // the blocks whose rates it can change (itself included)
};

}  // namespace

JacobianPattern jacobian_pattern(const Network& network, const Island& island,
                                 const std::vector<int>& solved) {
  std::vector<Block> blocks;
  // Admittance index -> its block, by the admittance's address (maps name them by pointer).
  std::vector<std::pair<const Admittance*, int>> block_of_body;
  for (int j : island.admittances) {
    const Slot s = network.admittance_slot(j);
    if (s.state_size == 0) continue;
    block_of_body.emplace_back(network.admittances()[static_cast<std::size_t>(j)].get(),
                               static_cast<int>(blocks.size()));
    blocks.push_back({s.state_offset, s.state_size, {}, {}});
  }
  std::sort(block_of_body.begin(), block_of_body.end());
  std::vector<int> own_block(island.impedances.size(), -1);
  for (std::size_t k = 0; k < island.impedances.size(); ++k) {
    const Slot s = network.impedance_slot(island.impedances[k]);
    if (s.state_size == 0) continue;
    own_block[k] = static_cast<int>(blocks.size());
    blocks.push_back({s.state_offset, s.state_size, {}, {}});
  }
  for (Block& b : blocks) {
    const auto first = std::lower_bound(solved.begin(), solved.end(), b.offset);
    for (auto it = first; it != solved.end() && *it < b.offset + b.size; ++it) {
      b.columns.push_back(static_cast<int>(it - solved.begin()));
    }
    b.reach.push_back(static_cast<int>(&b - blocks.data()));
  }
  // Each element's clique: the bodies its map moves (those in the island with a state) and
  // its own state.
  std::vector<int> clique;
  for (std::size_t k = 0; k < island.impedances.size(); ++k) {
    clique.clear();
    for (const Admittance* body : network.map_of(island.impedances[k]).admittances()) {
      const auto it =
          std::lower_bound(block_of_body.begin(), block_of_body.end(), std::make_pair(body, -1));
      if (it != block_of_body.end() && it->first == body) clique.push_back(it->second);
    }
    if (own_block[k] >= 0) clique.push_back(own_block[k]);
    for (int a : clique) {
      auto& reach = blocks[static_cast<std::size_t>(a)].reach;
      reach.insert(reach.end(), clique.begin(), clique.end());
    }
  }
  for (Block& b : blocks) {
    std::sort(b.reach.begin(), b.reach.end());
    b.reach.erase(std::unique(b.reach.begin(), b.reach.end()), b.reach.end());
  }

  JacobianPattern pattern;
  pattern.rows.resize(solved.size());
  for (const Block& b : blocks) {
    if (b.columns.empty()) continue;
    std::vector<int> rows;
    for (int r : b.reach) {
      const auto& c = blocks[static_cast<std::size_t>(r)].columns;
      rows.insert(rows.end(), c.begin(), c.end());
    }
    std::sort(rows.begin(), rows.end());
    for (int column : b.columns) pattern.rows[static_cast<std::size_t>(column)] = rows;
  }
  // Greedy colouring: a block joins the first colour none of whose blocks reaches a row it
  // reaches.
  struct Colour {
    std::vector<char> reached;  // per block
    std::vector<int> members;
    std::size_t width = 0;  // the most solved columns of a member
  };
  std::vector<Colour> colours;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Block& block = blocks[b];
    if (block.columns.empty()) continue;
    Colour* chosen = nullptr;
    for (Colour& c : colours) {
      const bool clash = std::any_of(block.reach.begin(), block.reach.end(), [&](int r) {
        return c.reached[static_cast<std::size_t>(r)] != 0;
      });
      if (!clash) {
        chosen = &c;
        break;
      }
    }
    if (chosen == nullptr) {
      colours.push_back({std::vector<char>(blocks.size(), 0), {}, 0});
      chosen = &colours.back();
    }
    for (int r : block.reach) chosen->reached[static_cast<std::size_t>(r)] = 1;
    chosen->members.push_back(static_cast<int>(b));
    chosen->width = std::max(chosen->width, block.columns.size());
  }
  for (const Colour& c : colours) {
    for (std::size_t k = 0; k < c.width; ++k) {
      std::vector<int> group;
      for (int b : c.members) {
        const auto& columns = blocks[static_cast<std::size_t>(b)].columns;
        if (k < columns.size()) group.push_back(columns[k]);
      }
      pattern.groups.push_back(std::move(group));
    }
  }
  return pattern;
}

}  // namespace stiction::core
