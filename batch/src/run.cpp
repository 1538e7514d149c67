#include "simpartner/batch/run.h"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "observer.h"
#include "simpartner/bus_url.h"
#include "simpartner/child_process.h"
#include "simpartner/programs.h"
#include "simpartner/text.h"

namespace simpartner::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// `name` found as a shell would (FindProgram: this build or install
// first), else the name itself, which then cannot start and says so.
std::string Program(const std::string& name) {
  const std::string found = FindProgram(name);
  return found.empty() ? name : found;
}

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<std::string> SimArgv(const BatchFile& batch, const PlannedRun& run,
                                 const std::string& url) {
  // No parameters file: the built-in defaults and the batch's values, so a
  // run does not depend on the directory it runs in.
  // A sweep's environment (a world per run) comes after the batch's and
  // wins, as the last of a key on a command line does; robot is the sim's
  // --robot=NAME.
  std::vector<std::string> argv = {Program("simpartner-sim"), "--params", "/dev/null",
                                   "--environment=" + batch.world, "--startPaused=1",
                                   "--speed=0", "--duration=" + ShortestNumber(batch.duration),
                                   "--lcm-url", url};
  if (!batch.robot.empty()) argv.insert(argv.end(), {"--robot", batch.robot});
  for (const auto& [key, value] : run.parameters) argv.push_back("--" + key + "=" + value);
  return argv;
}

std::vector<std::string> ControllerOrSequencer(const BatchFile& batch, const PlannedRun& run,
                                               const std::string& url) {
  if (!batch.sequence.empty())
    return {Program("simpartner-sequencer"), batch.sequence, "--lcm-url", url, "--from-zero",
            "--resume", "--quiet"};
  std::vector<std::string> argv = ControllerArgv(batch, run, url);
  if (!argv.empty()) argv[0] = Program(argv[0]);
  return argv;
}

std::string FileText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// What a process that ended early wrote (why, as a rule), on one line.
std::string LogInOneLine(const fs::path& log) {
  std::string text = Trim(FileText(log));
  for (char& c : text)
    if (c == '\n') c = ' ';
  return text.size() > 400 ? text.substr(0, 400) + " ..." : text;
}

// The run's processes, stopped (and reaped) when it goes. Each gets
// SIGTERM if the batch dies, even by kill -9; the controller runs in a
// process group of its own, stopped whole: what it started goes with it.
constexpr ChildOptions kRunProcess{/*own_group=*/false, /*stop_with_parent=*/true};
constexpr ChildOptions kControllerProcess{/*own_group=*/true, /*stop_with_parent=*/true};

struct Processes {
  std::unique_ptr<ChildProcess> logger, sim, controller;
  std::filesystem::path sim_log;
  ~Processes() {
    for (auto* p : {&controller, &sim, &logger})
      if (*p) (*p)->Signal(SIGTERM);
    for (auto* p : {&controller, &sim, &logger})
      if (*p && !(*p)->Wait(std::chrono::seconds(60))) (*p)->Signal(SIGKILL);
  }
};

std::string ExitText(const std::string& who, int status) {
  return who + (status >= 128 ? " killed by signal " + std::to_string(status - 128)
                              : " exit " + std::to_string(status));
}

// Starts the logger and waits (up to 30 s) until it logs: it must hear the
// model before the sim steps.
bool StartLogger(const RunContext& context, const std::string& url, const std::string& tag,
                 const fs::path& dir, Processes* p, std::string* status) {
  // A spool of the run's own: loggers running side by side cannot share one.
  std::vector<std::string> argv = {Program("simpartner-logger"), "--lcm-url", url, "--tag", tag,
                                   "--spool", (dir / "logger-spool").string()};
  argv.insert(argv.end(), context.logger_args.begin(), context.logger_args.end());
  p->logger = std::make_unique<ChildProcess>(argv, (dir / "logger.log").string(), kRunProcess);
  const Clock::time_point start = Clock::now();
  while (SecondsSince(start) < 30) {
    if (FileText(dir / "logger.log").find("logging ") != std::string::npos) return true;
    if (const auto ended = p->logger->Wait(std::chrono::milliseconds(50))) {
      *status = ExitText("logger", *ended) + " before logging: " + LogInOneLine(dir / "logger.log");
      return false;
    }
  }
  *status = "logger not logging after 30 s (see logger.log)";
  return false;
}

// The observer joins the paused sim as a lock-step controller before the
// controller starts (observer.h: no state lost on a loaded machine).
// Returns "" or what failed.
std::string JoinPacer(Processes* p, RunObserver* observer) {
  const Clock::time_point start = Clock::now();
  while (!observer->joined()) {
    if (!observer->pace_problem().empty())
      return "the sim refused the batch's lock-step join: " + observer->pace_problem();
    if (const auto ended = p->sim->Wait(std::chrono::milliseconds(0)))
      return ExitText("sim", *ended) + " before it ran: " + LogInOneLine(p->sim_log);
    if (SecondsSince(start) > 60) return "the sim did not answer a lock-step join in 60 s (see sim.log)";
    observer->AskToJoin();
    observer->Pump(20, 250);
  }
  return "";
}

// Follows the run until the sim ends (its duration) or the timeout; then
// gives the controller 10 s to end by itself. Returns "" or what failed.
std::string Follow(const RunContext& context, Processes* p, RunObserver* observer,
                   Clock::time_point start) {
  std::optional<int> sim_status;
  while (!(sim_status = p->sim->Wait(std::chrono::milliseconds(0)))) {
    observer->Pump(20);
    // A controller that fails ends the run at once (the sim would wait for
    // it, paused or at its tick, until the timeout).
    if (const auto ended = p->controller->Wait(std::chrono::milliseconds(0)); ended && *ended != 0)
      return ExitText("controller", *ended) + " while the sim ran (see controller.log)";
    if (SecondsSince(start) > context.timeout)
      return "timeout after " + ShortestNumber(context.timeout) + " s at step " +
             std::to_string(observer->last_step());
  }
  observer->Pump(200, 5000);  // the last states still on their way
  if (*sim_status != 0) return ExitText("sim", *sim_status) + " (see sim.log)";
  const std::optional<int> controller = p->controller->Wait(std::chrono::seconds(10));
  if (!controller) return "the controller did not end within 10 s of the sim (see controller.log)";
  if (*controller != 0) return ExitText("controller", *controller) + " (see controller.log)";
  return "";
}

}  // namespace

RunResult RunOne(const BatchFile& batch, const PlannedRun& run, const RunContext& context) {
  RunResult result;
  result.index = run.index;
  result.tag = RunTag(batch, run);
  const fs::path dir = fs::path(context.results_dir) / "runs" / std::to_string(run.index);
  fs::create_directories(dir);
  result.log_dir = dir.string();
  const Clock::time_point start = Clock::now();
  try {
    const std::string url = PrivateBusUrl(::getpid(), run.index % 100);
    RunObserver observer(url, batch.figures);
    Processes p;
    std::string failure;
    if (!context.log || StartLogger(context, url, result.tag, dir, &p, &failure)) {
      p.sim_log = dir / "sim.log";
      p.sim = std::make_unique<ChildProcess>(SimArgv(batch, run, url), p.sim_log.string(), kRunProcess);
      failure = JoinPacer(&p, &observer);
      if (failure.empty()) {
        p.controller = std::make_unique<ChildProcess>(ControllerOrSequencer(batch, run, url),
                                                      (dir / "controller.log").string(),
                                                      kControllerProcess);
        failure = Follow(context, &p, &observer, start);
      }
    }
    result.ok = failure.empty();
    result.status = result.ok ? "ok" : failure;
    result.last_step = observer.last_step();
    result.sim_time = observer.sim_time();
    result.states = observer.states();
    // The sim ends after the step at its duration (simpartner-sim).
    const double dt = observer.step_size();
    result.state_hash =
        dt > 0 ? observer.Hash(static_cast<int64_t>(std::llround(batch.duration / dt))) : "";
    result.figures = observer.Figures();
  } catch (const std::exception& e) {
    result.ok = false;
    result.status = std::string("could not run: ") + e.what();
  }
  result.wall_seconds = SecondsSince(start);
  return result;
}

std::string ResultPath(const std::string& results_dir, int index) {
  return (fs::path(results_dir) / "runs" / std::to_string(index) / "result.txt").string();
}

void WriteResult(const RunResult& r, const std::string& path) {
  const std::string temporary = path + ".new";
  {
    std::ofstream out(temporary);
    out << "index=" << r.index << "\nok=" << (r.ok ? 1 : 0) << "\nstatus=" << r.status
        << "\ntag=" << r.tag << "\nlast_step=" << r.last_step
        << "\nsim_time=" << ShortestNumber(r.sim_time)
        << "\nwall_seconds=" << FormatFixed(r.wall_seconds, 3) << "\nstate_hash=" << r.state_hash
        << "\nstates=" << r.states << "\nfigures=";
    for (size_t i = 0; i < r.figures.size(); ++i) out << (i ? " " : "") << ShortestNumber(r.figures[i]);
    out << "\nlog_dir=" << r.log_dir << "\n";
  }
  fs::rename(temporary, path);  // whole or not at all: a resumed batch trusts it
}

namespace {

// One "key=value" line of a result file into r; throws on a bad number.
void ReadResultLine(const std::string& line, RunResult* r) {
  const size_t eq = line.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("no '=' in '" + line + "'");
  const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
  if (key == "index") r->index = std::stoi(value);
  else if (key == "ok") r->ok = value == "1";
  else if (key == "status") r->status = value;
  else if (key == "tag") r->tag = value;
  else if (key == "last_step") r->last_step = std::stoll(value);
  else if (key == "sim_time") r->sim_time = std::stod(value);
  else if (key == "wall_seconds") r->wall_seconds = std::stod(value);
  else if (key == "state_hash") r->state_hash = value;
  else if (key == "states") r->states = std::stoll(value);
  else if (key == "log_dir") r->log_dir = value;
  else if (key == "figures") {
    std::istringstream words(value);
    for (std::string w; words >> w;) r->figures.push_back(std::stod(w));
  }
}

}  // namespace

std::optional<RunResult> ReadResult(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  RunResult r;
  try {
    for (std::string line; std::getline(in, line);) ReadResultLine(line, &r);
  } catch (const std::exception&) {
    return std::nullopt;  // not ours, or damaged: the run is done again
  }
  return r;
}

}  // namespace simpartner::batch
