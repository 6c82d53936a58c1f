// "Did you mean ...": the known name nearest to a misspelt one, by edit distance, if it is
// near enough to be a likely typo (at most a third of the longer name's characters differ).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rpsd::config {

// Insertions, deletions and substitutions that turn a into b (Levenshtein).
std::size_t edit_distance(std::string_view a, std::string_view b);

std::optional<std::string> closest_name(std::string_view name, const std::vector<std::string_view>& known);

// " (did you mean \"x\"?)" or "".
std::string did_you_mean(std::string_view name, const std::vector<std::string_view>& known);

}  // namespace rpsd::config
