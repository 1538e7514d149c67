#include "processes.h"

#include <cstdlib>
#include <fstream>

#include "programs.h"
#include "simpartner/child_process.h"
#include "text_file.h"

namespace simpartner::test_support {

bool ProcessRunning(pid_t pid) {
  if (pid <= 0) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  // pid (comm) state ...: the comm may hold spaces and parentheses.
  const size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

ProgramRun RunToEnd(const std::vector<std::string>& argv, const std::string& log,
                    std::chrono::milliseconds timeout) {
  ProgramRun run;
  {
    ChildProcess child(argv, log);
    run.status = child.Wait(timeout).value_or(-1);
  }  // killed and reaped here if it did not end
  run.output = ReadText(log);
  return run;
}

ProgramRun InstallThisBuild(const std::string& prefix, const std::string& component, const std::string& log) {
  return RunToEnd({SP_CMAKE, "--install", BinaryDir(), "--prefix", prefix, "--component", component}, log,
                  std::chrono::minutes(5));
}

std::vector<std::string> OnDisplay(const std::string& display, const std::vector<std::string>& argv) {
  std::vector<std::string> wrapped = {
      "/usr/bin/env", "DISPLAY=" + display,
      "LSAN_OPTIONS=suppressions=" + SourceDir() + "/tests/viewer/lsan.supp",
      "LD_PRELOAD=" SP_KEEP_LOADED_LIB, "ASAN_OPTIONS=" + AsanOptions()};
  wrapped.insert(wrapped.end(), argv.begin(), argv.end());
  return wrapped;
}

std::vector<std::string> InDirectory(const std::string& dir, const std::vector<std::string>& argv) {
  std::vector<std::string> wrapped = {"/usr/bin/env", "--chdir=" + dir};
  wrapped.insert(wrapped.end(), argv.begin(), argv.end());
  return wrapped;
}

std::string AsanOptions() {
  const char* given = std::getenv("ASAN_OPTIONS");
  return (given != nullptr && *given != '\0' ? std::string(given) + ":" : std::string()) +
         "verify_asan_link_order=0";
}

std::vector<std::string> XdotoolCommand(const std::string& display, const std::vector<std::string>& args) {
  std::vector<std::string> argv = {"/usr/bin/env", "DISPLAY=" + display, "/usr/bin/xdotool"};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

ProgramRun RunXdotool(const std::string& display, const std::vector<std::string>& args,
                      const std::string& log) {
  return RunToEnd(XdotoolCommand(display, args), log, std::chrono::seconds(10));
}

}  // namespace simpartner::test_support
