#include "simpartner/parameters.h"

#include <gtest/gtest.h>

namespace simpartner {
namespace {

TEST(Parameters, Placeholder) { EXPECT_EQ(Parameters().stepsize, 0.001); }

}  // namespace
}  // namespace simpartner
