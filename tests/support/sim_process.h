// simpartner-sim of this build as the process tests start it: a world, a
// bus, flags, its output in a log file; killed and reaped when the object
// goes (simpartner/child_process.h). The test talks to it over the bus
// (BusListener), never through the sim library.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/child_process.h"

namespace simpartner::test_support {

// argv of this build's simpartner-sim on `world` (a path) and `url`, with
// no parameters file (--params /dev/null: the built-in defaults, whatever
// the tree's parameters.txt says), then `flags`.
std::vector<std::string> SimCommand(const std::string& world, const std::string& url,
                                    const std::vector<std::string>& flags = {});

class SimProcess {
 public:
  // Starts SimCommand(world, url, flags) with stdout and stderr to `log`.
  SimProcess(const std::string& world, const std::string& url, std::string log,
             const std::vector<std::string>& flags = {});

  // Until it says it runs (its bus open and no other sim found on it):
  // false when it ended first or `seconds` passed.
  bool WaitUntilRunning(double seconds);
  // SIGTERM (ends a run as SIM_CONTROL quit does), then its exit status;
  // std::nullopt when it is still running after `timeout`.
  std::optional<int> Stop(std::chrono::milliseconds timeout = std::chrono::seconds(10));

  // Exit status once it has ended (ChildProcess::Wait).
  std::optional<int> Wait(std::chrono::milliseconds timeout) { return child_.Wait(timeout); }
  void Signal(int signal) { child_.Signal(signal); }
  bool running() { return child_.running(); }
  // What it has printed so far.
  std::string Log() const;

 private:
  std::string log_;
  ChildProcess child_;
};

}  // namespace simpartner::test_support
