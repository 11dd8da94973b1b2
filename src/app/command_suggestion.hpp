// A mistyped command (`stiction rn`): which command the user probably meant. CLI11 alone says
// "A subcommand is required", which does not tell a typo from a missing command.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace stiction::app {

// The command nearest `word` by edit distance (insertions, deletions, substitutions and
// swaps of neighbours count one each), if it is near enough to be a typo: at most one edit
// for words of up to four letters, two for longer ones, or `word` being a prefix of exactly
// one command ("sw" -> "sweep").
std::optional<std::string> nearest_command(const std::string& word,
                                           const std::vector<std::string>& commands);

// The message for an unknown command: "error: unknown command 'rn'; did you mean 'run'?",
// or the list of commands when none is near.
std::string unknown_command_message(const std::string& word,
                                    const std::vector<std::string>& commands);

}  // namespace stiction::app
