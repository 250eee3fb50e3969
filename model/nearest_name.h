// Suggestions for a name that is not there: the known names nearest to it
// (Levenshtein edit distance, letters compared without case; V. I.
// Levenshtein, Soviet Physics Doklady 10 (1966) 707-710), for messages such
// as "no channel 'main3.Fy' (nearest: main3.fy, main3.fx, main2.fy)".
#pragma once

#include <string>
#include <vector>

namespace evas {

/// Edit distance between a and b, letters compared without case.
std::size_t edit_distance(const std::string& a, const std::string& b);

/// Up to `count` of `names` nearest to `wanted`, nearest first (ties in the
/// names' order); a glob's '*' and '?' are dropped from `wanted` first.
std::vector<std::string> nearest_names(const std::string& wanted,
                                       const std::vector<std::string>& names,
                                       std::size_t count = 3);

/// "nearest: a, b, c" (or "" when there are no names), for messages; with
/// `total` the number of names, and more than `count` of them, adds "; N in all".
std::string nearest_text(const std::string& wanted, const std::vector<std::string>& names,
                         std::size_t count = 3);

}  // namespace evas
