// The words of a drawn text as the "never cut mid-word" checks see them.
#pragma once

#include <cctype>
#include <string>
#include <vector>

namespace stiction::testing {

// The ASCII letter-and-digit runs of a text ("…", spaces, brackets, '_' and '.' separate
// them).
inline std::vector<std::string> word_runs(const std::string& text) {
  std::vector<std::string> runs;
  std::string current;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      current += c;
    } else if (!current.empty()) {
      runs.push_back(current);
      current.clear();
    }
  }
  if (!current.empty()) runs.push_back(current);
  return runs;
}

}  // namespace stiction::testing
