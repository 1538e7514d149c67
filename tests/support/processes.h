// Running programs from a test, on top of simpartner/child_process.h: a run
// to its end with what it printed, this build installed into a prefix, a
// GUI program on a test's X display under the sanitized build, and xdotool
// on that display.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

namespace simpartner::test_support {

// A program run to its end: its exit status (128 + signal when killed; -1
// when it was still running at the timeout, and then killed) and everything
// it printed on stdout and stderr.
struct ProgramRun {
  int status = -1;
  std::string output;
};

// Runs argv with its output to the file `log`, waits at most `timeout`.
ProgramRun RunToEnd(const std::vector<std::string>& argv, const std::string& log,
                    std::chrono::milliseconds timeout);

// True while a process with this pid runs: a zombie has ended (a process
// in a session of its own is reaped by init, up to a second later).
bool ProcessRunning(pid_t pid);

// `cmake --install` of this build's `component` ("programs", "client")
// into `prefix`, run to its end (5 minutes at most).
ProgramRun InstallThisBuild(const std::string& prefix, const std::string& component, const std::string& log);

// argv on X display `display` (":N"), for the programs that load SDL, GL and
// X (viewer, keyboard teleop). Under ASan those libraries keep allocations
// for the life of the process: LeakSanitizer gets tests/viewer/lsan.supp,
// and tests/viewer/keep_libraries_loaded.c is preloaded so that its
// reports can name Mesa's driver (AsanOptions() then allows the preload).
std::vector<std::string> OnDisplay(const std::string& display, const std::vector<std::string>& argv);

// The caller's ASAN_OPTIONS, and no complaint that a preloaded library comes
// before ASan's runtime.
std::string AsanOptions();

// argv run in directory `dir` (where a program writes its own files).
std::vector<std::string> InDirectory(const std::string& dir, const std::vector<std::string>& argv);

// xdotool with `args` on display `display` (real key presses through XTEST).
std::vector<std::string> XdotoolCommand(const std::string& display, const std::vector<std::string>& args);
// XdotoolCommand run to its end (10 s at most), its output into `log`.
ProgramRun RunXdotool(const std::string& display, const std::vector<std::string>& args,
                      const std::string& log);

}  // namespace simpartner::test_support
