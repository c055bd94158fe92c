// edit_distance.hpp - how far apart two words are, for "did you mean ...?"
// suggestions on a mistyped subcommand.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace clrt {

// The optimal string alignment distance between a and b: the fewest
// insertions, deletions, substitutions and swaps of two adjacent characters
// that turn one into the other ("rendr" -> "render": 1, "redner" -> "render":
// 1, "" -> "abc": 3). Case-sensitive.
size_t edit_distance(std::string_view a, std::string_view b);

// The candidate nearest to `word` (the first of equals), if it is close
// enough to be a typo: at most 2 edits, and fewer than the word's own length
// ("clr" -> "clear", but "x" -> nothing). "" when none is.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace clrt
