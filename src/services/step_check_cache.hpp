// A small on-disk cache of step checks (app/step_check.hpp), so that running a scene again
// does not pay for its analysis again. An entry is a JSON file named by a hash of its key;
// the key (the program's own identity, the scene's content after overrides and the settings
// the analysis depends on) is stored in the entry and compared in full, so a hash collision
// or a stale entry is a miss, never a wrong answer. The program's identity (size and
// modification time of the running executable) changes with every build, so a changed
// analysis never reads old results.
//
// Where: $STICTION_CACHE_DIR, else $XDG_CACHE_HOME/stiction, else $HOME/.cache/stiction;
// STICTION_CACHE_DIR=off disables it. Every failure (no such directory, read-only, a corrupt
// entry, a full disk) is a silent miss: the cache only saves time.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace stiction::services {

class StepCheckCache {
 public:
  // `key`: everything the cached value depends on, as text.
  explicit StepCheckCache(std::string key);
  std::optional<nlohmann::json> load() const;
  void store(const nlohmann::json& value) const;

 private:
  std::string key_;
  std::string file_;  // empty: no cache
};

}  // namespace stiction::services
