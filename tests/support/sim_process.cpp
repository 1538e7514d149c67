#include "sim_process.h"

#include <signal.h>

#include "programs.h"
#include "text_file.h"
#include "wait.h"

namespace simpartner::test_support {

std::vector<std::string> SimCommand(const std::string& world, const std::string& url,
                                    const std::vector<std::string>& flags) {
  std::vector<std::string> args = {"--params", "/dev/null", "--environment=" + world, "--lcm-url", url};
  args.insert(args.end(), flags.begin(), flags.end());
  return BuiltCommand("simpartner-sim", args);
}

SimProcess::SimProcess(const std::string& world, const std::string& url, std::string log,
                       const std::vector<std::string>& flags)
    : log_(std::move(log)), child_(SimCommand(world, url, flags), log_) {}

bool SimProcess::WaitUntilRunning(double seconds) {
  // sim_core/main.cpp prints this once its bus is open and the probe for
  // another simulation found none.
  auto says_running = [&] { return Log().find("simpartner-sim: running") != std::string::npos; };
  WaitFor([&] { return says_running() || !child_.running(); }, seconds, std::chrono::milliseconds(20));
  return says_running();
}

std::optional<int> SimProcess::Stop(std::chrono::milliseconds timeout) {
  child_.Signal(SIGTERM);
  return child_.Wait(timeout);
}

std::string SimProcess::Log() const { return ReadText(log_); }

}  // namespace simpartner::test_support
