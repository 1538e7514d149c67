// Case-insensitive Levenshtein distance, for the "did you mean" hints of
// every program (parameter keys, actuator and sensor names).
#pragma once

#include <cstddef>
#include <string>

namespace simpartner {

size_t EditDistance(const std::string& a, const std::string& b);

}  // namespace simpartner
