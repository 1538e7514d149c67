// CsvField: RFC 4180 quoting, and text a spreadsheet would run as a
// formula written as text.
#include <gtest/gtest.h>

#include "simpartner/csv_field.h"

namespace simpartner {
namespace {

TEST(CsvField, QuotesWhatRfc4180Quotes) {
  EXPECT_EQ(CsvField("FrontChassis"), "FrontChassis");
  EXPECT_EQ(CsvField(""), "");
  EXPECT_EQ(CsvField("a,b"), "\"a,b\"");
  EXPECT_EQ(CsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
}

TEST(CsvField, AFormulaIsWrittenAsText) {
  EXPECT_EQ(CsvField("=HYPERLINK(\"http://x\",\"y\")"), "\"'=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\"");
  EXPECT_EQ(CsvField("+cmd|' /C calc'!A0"), "\"'+cmd|' /C calc'!A0\"");
  EXPECT_EQ(CsvField("-2+3"), "\"'-2+3\"");
  EXPECT_EQ(CsvField("@SUM(A1)"), "\"'@SUM(A1)\"");
  EXPECT_EQ(CsvField("\t=1"), "\"'\t=1\"");
  EXPECT_EQ(CsvField("\r=1"), "\"'\r=1\"");
  EXPECT_EQ(CsvField("-"), "\"'-\"");
  EXPECT_EQ(CsvField("-inf"), "\"'-inf\"");
}

TEST(CsvField, ANumberStaysANumber) {
  EXPECT_EQ(CsvField("-1.5"), "-1.5");
  EXPECT_EQ(CsvField("+2e3"), "+2e3");
  EXPECT_EQ(CsvField("-0"), "-0");
}

}  // namespace
}  // namespace simpartner
