#include "simpartner/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <thread>

#include "../support/processes.h"
#include "../support/text_file.h"

namespace simpartner {
namespace {

using std::chrono::milliseconds;

bool EndsWithin(pid_t pid, milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (test_support::ProcessRunning(pid)) {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(milliseconds(10));
  }
  return true;
}

// A shell that starts `sleep 30` and waits: the sleep's pid, from its log.
pid_t StartedSleep(const std::filesystem::path& log) {
  for (int i = 0; i < 500; ++i) {
    const std::string text = test_support::ReadText(log);
    if (!text.empty() && text.back() == '\n') return static_cast<pid_t>(std::stol(text));
    std::this_thread::sleep_for(milliseconds(10));
  }
  return -1;
}

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

// In a group of its own, a signal reaches what the program started too
// (a controller's helpers); without, the helper runs on.
TEST(ChildProcess, OwnGroupSignalReachesWhatItStarted) {
  const auto log = std::filesystem::temp_directory_path() /
                   ("sp_child_group_" + std::to_string(::getpid()) + ".log");
  const std::vector<std::string> shell = {"/bin/sh", "-c", "sleep 30 & echo $!; wait"};
  {
    ChildProcess grouped(shell, log.string(), ChildOptions{/*own_group=*/true, /*stop_with_parent=*/false});
    const pid_t helper = StartedSleep(log);
    ASSERT_GT(helper, 0);
    grouped.Signal(SIGTERM);
    EXPECT_EQ(grouped.Wait(milliseconds(5000)), 128 + SIGTERM);
    EXPECT_TRUE(EndsWithin(helper, milliseconds(5000))) << "the helper outlived its group's SIGTERM";
  }
  {
    ChildProcess alone(shell, log.string());
    const pid_t helper = StartedSleep(log);
    ASSERT_GT(helper, 0);
    alone.Signal(SIGTERM);
    EXPECT_EQ(alone.Wait(milliseconds(5000)), 128 + SIGTERM);
    EXPECT_FALSE(EndsWithin(helper, milliseconds(300))) << "without a group of its own the helper runs on";
    ::kill(helper, SIGKILL);
  }
  std::filesystem::remove(log);
}

// stop_with_parent: SIGTERM when the thread that started it ends (here a
// thread, as the parent process's death would); without, it runs on.
TEST(ChildProcess, StopWithParentEndsItWithTheThreadThatStartedIt) {
  auto start_in_thread = [](ChildOptions options) {
    std::unique_ptr<ChildProcess> child;
    std::thread([&] { child = std::make_unique<ChildProcess>(std::vector<std::string>{"/bin/sleep", "30"},
                                                             "/dev/null", options); })
        .join();
    return child;
  };
  const auto stopped = start_in_thread(ChildOptions{/*own_group=*/false, /*stop_with_parent=*/true});
  EXPECT_EQ(stopped->Wait(milliseconds(5000)), 128 + SIGTERM);
  const auto orphan = start_in_thread(ChildOptions{});
  EXPECT_FALSE(orphan->Wait(milliseconds(300)).has_value()) << "it ran on without stop_with_parent";
}

}  // namespace
}  // namespace simpartner
