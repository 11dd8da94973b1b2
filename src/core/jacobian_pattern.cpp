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
  int admittance = -1;       // the network's index of its body, or -1 (an element's own state)
  std::vector<int> columns;  // its solved entries, as indices into `solved`
  std::vector<int> reach;    // the blocks whose rates it can change (itself included)
};

// The star of a colour's member blocks (the header): appended to pattern.stars if it is
// small enough and exact enough to use; its index, or -1.
int add_star(const Network& network, const Island& island, const std::vector<Block>& blocks,
             const std::vector<std::vector<int>>& cliques, const std::vector<int>& members,
             JacobianPattern& pattern) {
  std::vector<char> member(blocks.size(), 0), in_star(blocks.size(), 0);
  for (int b : members)
    member[static_cast<std::size_t>(b)] = in_star[static_cast<std::size_t>(b)] = 1;
  Island star;
  for (std::size_t k = 0; k < cliques.size(); ++k) {
    const auto& clique = cliques[k];
    if (std::none_of(clique.begin(), clique.end(),
                     [&](int b) { return member[static_cast<std::size_t>(b)] != 0; })) {
      continue;
    }
    star.impedances.push_back(island.impedances[k]);
    for (int b : clique) in_star[static_cast<std::size_t>(b)] = 1;
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (in_star[b] == 0) continue;
    const Block& block = blocks[b];
    for (int e = block.offset; e < block.offset + block.size; ++e) star.states.push_back(e);
  }
  // Its cost by the measure evaluations are counted in (state entries): an arm's star holds
  // the whole arm, however few of its elements.
  if (static_cast<double>(star.states.size()) >
      kStarShare * static_cast<double>(island.states.size())) {
    return -1;
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (in_star[b] == 0) continue;
    const Block& block = blocks[b];
    if (block.admittance < 0) continue;
    // A neighbour sees only the star's forces: its rows are right only if its rate is
    // affine in them.
    const auto& body = network.admittances()[static_cast<std::size_t>(block.admittance)];
    if (member[b] == 0 && !body->affine_in_input()) return -1;
    star.admittances.push_back(block.admittance);
  }
  std::sort(star.admittances.begin(), star.admittances.end());
  std::sort(star.states.begin(), star.states.end());
  pattern.stars.push_back(std::move(star));
  return static_cast<int>(pattern.stars.size()) - 1;
}

}  // namespace

JacobianPattern jacobian_pattern(const Network& network, const Island& island,
                                 const std::vector<int>& solved, bool use_stars) {
  std::vector<Block> blocks;
  // Admittance index -> its block, by the admittance's address (maps name them by pointer).
  std::vector<std::pair<const Admittance*, int>> block_of_body;
  for (int j : island.admittances) {
    const Slot s = network.admittance_slot(j);
    if (s.state_size == 0) continue;
    block_of_body.emplace_back(network.admittances()[static_cast<std::size_t>(j)].get(),
                               static_cast<int>(blocks.size()));
    blocks.push_back({s.state_offset, s.state_size, j, {}, {}});
  }
  std::sort(block_of_body.begin(), block_of_body.end());
  std::vector<int> own_block(island.impedances.size(), -1);
  for (std::size_t k = 0; k < island.impedances.size(); ++k) {
    const Slot s = network.impedance_slot(island.impedances[k]);
    if (s.state_size == 0) continue;
    own_block[k] = static_cast<int>(blocks.size());
    blocks.push_back({s.state_offset, s.state_size, -1, {}, {}});
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
  std::vector<std::vector<int>> cliques(island.impedances.size());
  for (std::size_t k = 0; k < island.impedances.size(); ++k) {
    std::vector<int>& clique = cliques[k];
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
  const bool stars_may_pay = use_stars && island.impedances.size() >= kStarElements;
  for (const Colour& c : colours) {
    const int star =
        stars_may_pay ? add_star(network, island, blocks, cliques, c.members, pattern) : -1;
    for (std::size_t k = 0; k < c.width; ++k) {
      std::vector<int> group;
      for (int b : c.members) {
        const auto& columns = blocks[static_cast<std::size_t>(b)].columns;
        if (k < columns.size()) group.push_back(columns[k]);
      }
      pattern.groups.push_back(std::move(group));
      pattern.group_star.push_back(star);
    }
  }
  return pattern;
}

}  // namespace stiction::core
