// Case-insensitive Levenshtein distance, for the "did you mean" hints of
// every program (options, commands, parameter keys, actuator and sensor
// names).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace simpartner {

size_t EditDistance(const std::string& a, const std::string& b);

// The candidate nearest to word, for a "did you mean" hint, or "" when
// none is near: at most one edit per two characters of word, and at most
// three (a swapped pair of letters is two). Of two as near, one that word
// begins wins ("of": "off", not "on"), else the first.
std::string NearestName(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace simpartner
