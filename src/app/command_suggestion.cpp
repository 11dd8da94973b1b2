#include "app/command_suggestion.hpp"

#include <algorithm>
#include <limits>

namespace stiction::app {
namespace {

// Optimal string alignment distance (Damerau-Levenshtein without repeated edits of a
// substring): "rn" -> "run" is 1, "comapre" -> "compare" is 1.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

}  // namespace

std::optional<std::string> nearest_command(const std::string& word,
                                           const std::vector<std::string>& commands) {
  const std::size_t allowed = word.size() <= 4 ? 1 : 2;
  std::optional<std::string> best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  bool tie = false;
  for (const std::string& c : commands) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best = c;
      best_distance = d;
      tie = false;
    } else if (d == best_distance) {
      tie = true;
    }
  }
  if (best && best_distance <= allowed && !tie) return best;
  std::vector<std::string> prefixed;
  for (const std::string& c : commands) {
    if (!word.empty() && c.rfind(word, 0) == 0) prefixed.push_back(c);
  }
  if (prefixed.size() == 1) return prefixed.front();
  return std::nullopt;
}

std::string unknown_command_message(const std::string& word,
                                    const std::vector<std::string>& commands) {
  std::string message = "error: unknown command '" + word + "'";
  if (const std::optional<std::string> near = nearest_command(word, commands)) {
    return message + "; did you mean '" + *near + "'?";
  }
  message += "; the commands are:";
  for (std::size_t i = 0; i < commands.size(); ++i) message += (i ? ", " : " ") + commands[i];
  return message + " (stiction --help)";
}

}  // namespace stiction::app
