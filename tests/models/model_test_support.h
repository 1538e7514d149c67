// Helpers of the loader tests that write model XML inline.
#pragma once

#include <gtest/gtest.h>

#include <string>

namespace simpartner::model::testing {

// 1-based line of the one line of xml that contains marker.
inline int LineOf(const std::string& xml, const std::string& marker) {
  const size_t at = xml.find(marker);
  EXPECT_NE(at, std::string::npos) << "marker '" << marker << "' not in the XML";
  EXPECT_EQ(xml.find(marker, at + 1), std::string::npos) << "marker '" << marker << "' twice";
  if (at == std::string::npos) return -1;
  int line = 1;
  for (size_t i = 0; i < at; ++i) line += xml[i] == '\n';
  return line;
}

// Identity rotation, translation (x, y, z): the original's 3x4 form.
inline std::string Pose(double x, double y, double z) {
  return "<transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>" + std::to_string(x) +
         "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>" + std::to_string(y) +
         "</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>" + std::to_string(z) +
         "</T23></transformation>";
}

}  // namespace simpartner::model::testing
