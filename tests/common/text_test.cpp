// The shared text helpers (common/.../text.h) and the one table of action
// spellings (command_shape.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "simpartner/command_shape.h"
#include "simpartner/command_t.hpp"
#include "simpartner/text.h"

namespace simpartner {
namespace {

TEST(TrimTest, DropsBlanksAtBothEndsOnly) {
  EXPECT_EQ(Trim("  a b \t\r\n"), "a b");
  EXPECT_EQ(Trim("\n\t "), "");
  EXPECT_EQ(Trim(""), "");
  EXPECT_EQ(Trim("x"), "x");
}

TEST(FormatNumberTest, SignificantDigitsAsPrintfG) {
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(1e6), "1e+06");
  EXPECT_EQ(FormatNumber(3.14159265358979), "3.14159");
  EXPECT_EQ(FormatNumber(3.14159265358979, 10), "3.141592654");
  EXPECT_EQ(FormatNumber(-0.0049), "-0.0049");
}

TEST(FormatNumberTest, NonFiniteValuesAreWords) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(FormatNumber(inf), "inf");
  EXPECT_EQ(FormatNumber(-inf), "-inf");
  // printf writes "-nan" for a NaN with its sign bit set; one word here.
  EXPECT_EQ(FormatNumber(-std::nan("")), "nan");
  EXPECT_EQ(FormatFixed(inf, 2), "inf");
  EXPECT_EQ(ShortestNumber(-inf), "-inf");
}

TEST(ShortestNumberTest, ReadsBackExactly) {
  EXPECT_EQ(ShortestNumber(0.1), "0.1");
  EXPECT_EQ(ShortestNumber(1000), "1000");
  EXPECT_EQ(ShortestNumber(1e-5), "1e-05");
  EXPECT_EQ(ShortestNumber(-0.0), "0");
  const double third = 1.0 / 3.0;
  EXPECT_EQ(std::stod(ShortestNumber(third)), third);
}

TEST(FormatFixedTest, FixedDecimals) {
  EXPECT_EQ(FormatFixed(1354.14, 1), "1354.1");
  EXPECT_EQ(FormatFixed(-1.866, 2), "-1.87");
  EXPECT_EQ(FormatFixed(2, 0), "2");
}

TEST(ActionSpellingTest, EveryActionHasItsThreeSpellings) {
  // The spellings users and the database already know (sequencer/README.md,
  // logger's Command.action column), written out here.
  EXPECT_STREQ(SpellAction(command_t::ACTION_SET).word, "set");
  EXPECT_STREQ(SpellAction(command_t::ACTION_SET_STOPS).word, "stops");
  EXPECT_STREQ(SpellAction(command_t::ACTION_SET_STOPS).database, "SET_STOPS");
  EXPECT_STREQ(SpellAction(command_t::ACTION_SENSOR_PARAMS).word, "params");
  EXPECT_STREQ(SpellAction(command_t::ACTION_SENSOR_PARAMS).sequence_element, "sensorParams");
  EXPECT_STREQ(SpellAction(command_t::ACTION_SENSOR_PARAMS).database, "SENSOR_PARAMS");
  EXPECT_STREQ(SpellAction(command_t::ACTION_READ).database, "READ");
  EXPECT_STREQ(SpellAction(99).database, "UNKNOWN");
  EXPECT_STREQ(ActionName(99), "unknown action");
  EXPECT_EQ(ActionSpellings().size(), 5u);
}

TEST(ActionSpellingTest, SequenceElementsNameTheirActions) {
  EXPECT_EQ(ActionOfSequenceElement("stops"), command_t::ACTION_SET_STOPS);
  EXPECT_EQ(ActionOfSequenceElement("sensorParams"), command_t::ACTION_SENSOR_PARAMS);
  EXPECT_EQ(ActionOfSequenceElement("read"), command_t::ACTION_READ);
  EXPECT_EQ(ActionOfSequenceElement("params"), -1);  // the client's word, not an element
  EXPECT_EQ(ActionOfSequenceElement("command"), -1);
}

TEST(FitsTextTest, Utf8AndLength) {
  EXPECT_TRUE(FitsText("Wheel1", 255));
  EXPECT_TRUE(FitsText("Py\xc3\xb6r\xc3\xa4 \xe2\x82\xac \xf0\x9f\x98\x80", 255));
  EXPECT_FALSE(FitsText(std::string(256, 'a'), 255));
  EXPECT_FALSE(FitsText("\xc3", 255));              // cut short
  EXPECT_FALSE(FitsText("\xc0\xaf", 255));          // overlong
  EXPECT_FALSE(FitsText("\xed\xa0\x80", 255));      // surrogate
  EXPECT_FALSE(FitsText(std::string("a\0b", 3), 255));
}

}  // namespace
}  // namespace simpartner
