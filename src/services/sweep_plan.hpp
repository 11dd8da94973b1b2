// The points of `stiction sweep` (docs/sweeps.md): each `--vary KEY=LIST` gives one key and
// its values, LIST being `v1,v2,...` (TOML values, used as `--set KEY=v`) or
// `start:stop:count` (evenly spaced, both ends included) or `start:stop:count:log`
// (geometric). Several keys make the grid of all combinations (the last key varying
// fastest), or with `--zip` the element-wise pairs (equal lengths). A shard K/N takes the
// points K, K+N, K+2N, ... (0-based).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace stiction::services {

struct VaryKey {
  std::string key;                  // dotted scene key, as for --set
  std::vector<std::string> values;  // TOML text of each value
};

// Parses "KEY=LIST"; scene::InputError ("--vary ARG:1:COL: error: ...") on bad input.
VaryKey parse_vary(const std::string& argument);

struct SweepPoint {
  std::size_t index = 0;
  std::vector<std::string> values;  // one per key, in key order
};

// The most points a sweep plans (issue 39): a plan holds about 370 bytes a point before the
// first point runs (its values, its points and the plan's JSON), 0.37 GB at 1e6 points
// measured; at the earlier 1e7 it was about 4.9 GB.
inline constexpr std::size_t kMaxSweepPoints = 1'000'000;

// Grid (or zip) of the keys' values. InputError for zip lengths that differ, or more than
// `limit` points.
std::vector<SweepPoint> make_points(const std::vector<VaryKey>& keys, bool zip,
                                    std::size_t limit = kMaxSweepPoints);

struct Shard {
  std::size_t index = 0;  // K
  std::size_t count = 1;  // N
  bool sharded() const { return count > 1 || index > 0; }
  bool owns(std::size_t point) const { return point % count == index; }
};

// "K/N" with 0 <= K < N; InputError otherwise.
Shard parse_shard(const std::string& text);
// From SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_COUNT when both are
// set in the environment; nullopt otherwise. InputError for values that make no shard.
std::optional<Shard> shard_from_environment();

}  // namespace stiction::services
