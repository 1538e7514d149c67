// The trees under test and the programs built in them, in one place: every
// test that starts one of this build's programs takes its path from here.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace simpartner::test_support {

// The source tree and the build tree this test was built from.
std::string SourceDir();
std::string BinaryDir();

// A program of this build by its file name ("simpartner-sim",
// "simpartner-teleop-vpad", "drive_circle" ...): <build>/<folder>/<name>,
// the folder of the source that builds it (scripts/run --bin reads the
// same layout). Throws std::invalid_argument naming the programs it knows
// for any other name.
std::string BuiltProgram(std::string_view name);

// argv of a built program: its path, then `args`.
std::vector<std::string> BuiltCommand(std::string_view name, const std::vector<std::string>& args);

// A shipped world by file name: <source>/models/worlds/<file>.
std::string ShippedWorld(const std::string& file);

}  // namespace simpartner::test_support
