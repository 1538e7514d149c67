// A directory of the running test's own for the files its processes write
// (worlds, logs, a private server's data), unique per process and test.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace simpartner::test_support {

// <tmp>/<prefix><pid>_<test name>, emptied and created. `name_chars` cuts
// the test's name (a MariaDB socket under the directory must fit in 108
// bytes); with 0 the directory is <tmp>/<prefix><pid>.
inline std::filesystem::path FreshTestDir(const std::string& prefix,
                                          size_t name_chars = std::string::npos) {
  std::string leaf = prefix + std::to_string(::getpid());
  if (name_chars > 0)
    leaf += "_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name())
                      .substr(0, name_chars);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / leaf;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace simpartner::test_support
