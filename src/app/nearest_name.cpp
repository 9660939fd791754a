// Edit distance and the nearest-name suggestions of the command line.
#include "app/nearest_name.h"

#include <algorithm>
#include <numeric>

namespace glint {

size_t editDistance(const std::string& a, const std::string& b) {
  // The dynamic-programming table a row at a time: row[j] is the distance between the first
  // i characters of a and the first j of b; before and older are the two rows above, the
  // older one for transpositions.
  std::vector<size_t> older(b.size() + 1), before(b.size() + 1), row(b.size() + 1);
  std::iota(row.begin(), row.end(), size_t(0));
  for (size_t i = 1; i <= a.size(); ++i) {
    older.swap(before);
    before.swap(row);
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitution = before[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({before[j] + 1, row[j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], older[j - 2] + 1);
    }
  }
  return row[b.size()];
}

std::optional<std::string> nearestName(const std::string& word, const std::vector<std::string>& candidates) {
  // A third of the length: "--iter" (6) may be 2 edits from a suggestion, "-x" none beyond 1.
  const size_t allowed = std::clamp<size_t>(word.size() / 3, 1, 3);
  std::optional<std::string> best;
  size_t bestDistance = allowed + 1;
  for (const std::string& candidate : candidates) {
    const size_t d = editDistance(word, candidate);
    if (d < bestDistance) best = candidate, bestDistance = d;
  }
  return best;
}

std::vector<std::string> flagNames(const CLI::App& cmd) {
  std::vector<std::string> names;
  for (const CLI::Option* option : cmd.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  }
  return names;
}

std::string unknownFlagMessage(const CLI::App& cmd, const std::string& argument) {
  // "--iter=5" is the flag "--iter".
  const std::string flag = argument.substr(0, argument.find('='));
  const std::string help = "see glint " + cmd.get_name() + " --help";
  if (std::optional<std::string> near = nearestName(flag, flagNames(cmd)))
    return "unknown flag " + flag + "; did you mean " + *near + "? (" + help + ")";
  return "unknown flag " + flag + " (" + help + ")";
}

}  // namespace glint
