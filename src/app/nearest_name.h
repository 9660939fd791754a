// "Did you mean ...?" for mistyped commands and flags: the nearest known name by edit distance.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace glint {

// Edit distance (optimal string alignment): the fewest single-character insertions,
// deletions, substitutions and swaps of neighbours that turn a into b, each typo of one
// keystroke ("trian") counting 1.
size_t editDistance(const std::string& a, const std::string& b);

// The candidate nearest to `word`, if one is close enough to be a likely typo: at most a
// third of the word's length away (and at least 1, at most 3 edits). Ties go to the first.
std::optional<std::string> nearestName(const std::string& word, const std::vector<std::string>& candidates);

// Every flag `cmd` accepts, spelled as on the command line ("--iters", "-o").
std::vector<std::string> flagNames(const CLI::App& cmd);

// One line about an argument `cmd` does not know: "unknown flag --iter; did you mean
// --iters?" (or, without a near name, a pointer to --help).
std::string unknownFlagMessage(const CLI::App& cmd, const std::string& argument);

}  // namespace glint
