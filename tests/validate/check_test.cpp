// Verdicts and texts of the compared figures.
#include <gtest/gtest.h>

#include <cmath>

#include "simpartner/validate/check.h"

namespace simpartner::validate {
namespace {

TEST(ValidateCheck, RelativeToleranceIsAFractionOfTheTarget) {
  EXPECT_TRUE(Relative("r", 4.39, 4.0, 0.10, "m").pass);
  EXPECT_FALSE(Relative("r", 4.41, 4.0, 0.10, "m").pass);
  EXPECT_TRUE(Relative("r", 3.61, 4.0, 0.10, "m").pass);
  EXPECT_FALSE(Relative("r", 3.59, 4.0, 0.10, "m").pass);
  EXPECT_TRUE(Relative("negative target", -1.005, -1.0, 0.01, "").pass);
}

TEST(ValidateCheck, AbsoluteToleranceIsInTheUnit) {
  EXPECT_TRUE(Absolute("e", 0.0009, 0.0, 0.001, "m").pass);
  EXPECT_TRUE(Absolute("e", -0.001, 0.0, 0.001, "m").pass);
  EXPECT_FALSE(Absolute("e", 0.0011, 0.0, 0.001, "m").pass);
}

TEST(ValidateCheck, BoundsAreOneSided) {
  EXPECT_TRUE(AtLeast("v", 10.0, 10.0, "").pass);
  EXPECT_FALSE(AtLeast("v", 9.99, 10.0, "").pass);
  EXPECT_TRUE(AtMost("v", 1e-4, 1e-3, "m/s").pass);
  EXPECT_FALSE(AtMost("v", 2e-3, 1e-3, "m/s").pass);
}

TEST(ValidateCheck, NonFiniteMeasurementsFail) {
  EXPECT_FALSE(Relative("r", std::nan(""), 4.0, 0.1, "m").pass);
  EXPECT_FALSE(AtMost("v", std::nan(""), 1.0, "").pass);
  EXPECT_FALSE(AtLeast("v", std::nan(""), 1.0, "").pass);
  EXPECT_FALSE(AtLeast("v", INFINITY, 1.0, "").pass);
}

TEST(ValidateCheck, TextsCarryTheUnitAndTheKindOfTolerance) {
  const Check r = Relative("radius", 4.30, 4.01, 0.10, "m");
  EXPECT_EQ(r.MeasuredText(), "4.3 m");
  EXPECT_EQ(r.TargetText(), "4.01 m");
  EXPECT_EQ(r.ToleranceText(), "±10 %");
  const Check a = Absolute("error", 1.5e-13, 0.0, 1e-9, "m");
  EXPECT_EQ(a.MeasuredText(), "1.5e-13 m");
  EXPECT_EQ(a.ToleranceText(), "±1e-09 m");
  EXPECT_EQ(AtLeast("ratio", 12.0, 10.0, "").TargetText(), ">= 10");
  EXPECT_EQ(AtMost("v", 0.5, 1.0, "m/s").TargetText(), "<= 1 m/s");
  EXPECT_EQ(FormatNumber(0.0049050000001), "0.004905");
}

}  // namespace
}  // namespace simpartner::validate
