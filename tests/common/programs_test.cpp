// ProgramOnPath and FindProgram: a program to start, found as a shell
// finds it (posix_spawn does not look on PATH).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/test_dir.h"
#include "simpartner/programs.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

// PATH set for one test, and put back.
class PathSetTo {
 public:
  explicit PathSetTo(const std::string& path) {
    const char* old = std::getenv("PATH");
    had_ = old != nullptr;
    if (had_) old_ = old;
    ::setenv("PATH", path.c_str(), 1);
  }
  ~PathSetTo() {
    if (had_) ::setenv("PATH", old_.c_str(), 1);
    else ::unsetenv("PATH");
  }
  PathSetTo(const PathSetTo&) = delete;
  PathSetTo& operator=(const PathSetTo&) = delete;

 private:
  bool had_ = false;
  std::string old_;
};

void WriteProgram(const fs::path& path, fs::perms perms) {
  std::ofstream(path) << "#!/bin/sh\n";
  fs::permissions(path, perms);
}

TEST(ProgramOnPath, TheFirstExecutableFileInPathOrder) {
  const fs::path dir = test_support::FreshTestDir("sp_programs_");
  for (const char* folder : {"a", "b", "c"}) fs::create_directory(dir / folder);
  WriteProgram(dir / "a/sp_tool", fs::perms::owner_read | fs::perms::owner_write);
  WriteProgram(dir / "b/sp_tool", fs::perms::owner_all);
  WriteProgram(dir / "c/sp_tool", fs::perms::owner_all);
  fs::create_directory(dir / "a/sp_folder");  // a folder is no program
  // Empty entries (the current directory to a shell) are passed over.
  const PathSetTo path("::" + (dir / "a").string() + ":" + (dir / "b").string() + "::" +
                       (dir / "c").string() + ":");
  EXPECT_EQ(ProgramOnPath("sp_tool"), (dir / "b/sp_tool").string());
  EXPECT_EQ(ProgramOnPath("sp_folder"), "");
  EXPECT_EQ(ProgramOnPath("sp_no_such_tool"), "");
  EXPECT_EQ(FindProgram("sp_tool"), (dir / "b/sp_tool").string());
  // A path is taken as given, when it is an executable file.
  EXPECT_EQ(FindProgram((dir / "c/sp_tool").string()), (dir / "c/sp_tool").string());
  EXPECT_EQ(FindProgram((dir / "a/sp_tool").string()), "");
  EXPECT_EQ(FindProgram(""), "");
  fs::remove_all(dir);
}

TEST(ProgramOnPath, NoPathNoProgram) {
  const char* old = std::getenv("PATH");
  const std::string saved = old != nullptr ? old : "";
  ::unsetenv("PATH");
  EXPECT_EQ(ProgramOnPath("sh"), "");
  if (old != nullptr) ::setenv("PATH", saved.c_str(), 1);
}

}  // namespace
}  // namespace simpartner
