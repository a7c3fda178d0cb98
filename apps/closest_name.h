// The closest of a list of names to a misspelt one, by edit distance: what the command
// line suggests for an unknown subcommand or option ("did you mean 'run'?").
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace trackbed::apps {

/// Edits turning `a` into `b`: insertions, deletions, substitutions and transpositions
/// of neighbouring characters, each 1 (optimal string alignment distance).
std::size_t EditDistance(const std::string& a, const std::string& b);

/// The name in `names` closest to `word` (the first of equals), when it is within a
/// third of its length (at least 1 edit; leading dashes not counted), else nullopt:
/// "runn" → "run", "--seeed" → "--seed", "xyz" → nullopt.
std::optional<std::string> ClosestName(const std::string& word,
                                       const std::vector<std::string>& names);

}  // namespace trackbed::apps
