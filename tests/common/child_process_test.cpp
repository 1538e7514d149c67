#include "simpartner/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <stdexcept>

#include "../support/text_file.h"

namespace simpartner {
namespace {

using std::chrono::milliseconds;

TEST(ChildProcess, ReportsExitStatusAndOutput) {
  const auto log = std::filesystem::temp_directory_path() /
                   ("sp_child_" + std::to_string(::getpid()) + ".log");
  {
    ChildProcess child({"/bin/sh", "-c", "echo out; echo err >&2; exit 3"}, log.string());
    EXPECT_EQ(child.Wait(milliseconds(5000)), 3);
    EXPECT_FALSE(child.running());
  }
  EXPECT_EQ(test_support::ReadText(log), "out\nerr\n");
  std::filesystem::remove(log);
}

TEST(ChildProcess, StillRunningThenSignalled) {
  ChildProcess child({"/bin/sleep", "30"}, "/dev/null");
  EXPECT_FALSE(child.Wait(milliseconds(100)).has_value());
  EXPECT_TRUE(child.running());
  child.Signal(SIGTERM);
  EXPECT_EQ(child.Wait(milliseconds(5000)), 128 + SIGTERM);
}

TEST(ChildProcess, DestructorKillsWhatIsLeft) {
  pid_t pid = -1;
  {
    ChildProcess child({"/bin/sleep", "30"}, "/dev/null");
    pid = child.pid();
    ASSERT_GT(pid, 0);
  }
  // Reaped: the pid no longer names a child of ours.
  EXPECT_NE(::kill(pid, 0), 0);
}

TEST(ChildProcess, MissingProgramIsAnErrorNamingIt) {
  try {
    ChildProcess child({"/nonexistent/program"}, "/dev/null");
    FAIL() << "started a program that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/program"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace simpartner
