// Not-a-number and infinity, as the tests of checks feed them.
#pragma once

#include <limits>

namespace simpartner::test_support {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace simpartner::test_support
