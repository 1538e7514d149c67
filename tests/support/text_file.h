// The whole of a text file (a process's log, a written export) as a string,
// for tests that read what a real process wrote; "" when it cannot be read.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace simpartner::test_support {

inline std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace simpartner::test_support
