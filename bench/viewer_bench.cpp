// viewer_bench: how fast simpartner-viewer draws and what it costs, under a
// private Xvfb with Mesa's llvmpipe (software rendering), next to a
// simpartner-sim running at real time.
//
//   viewer_bench [--seconds N] [--width W --height H] [world.xml]
//
// Default world: models/worlds/test_track.xml (the heightfield track) with
// WorkPartner gen3 in place of its gen4 (a copy in a temporary directory).
// Prints, for the viewer drawing as fast as it can (--fps 0) and at its
// default cap (60 fps): frames per second, the viewer's CPU time as a
// fraction of one core (from /proc, startup excluded), the X server's
// share, and the sim's real-time factor meanwhile (from SIM_STATUS).
#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_line.h"
#include "simpartner/bus_signing.h"
#include "simpartner/control_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/viewer/xvfb.h"
#include "process_cpu.h"

namespace {

using Clock = std::chrono::steady_clock;
using simpartner::ChildProcess;
using simpartner::bench::ProcessCpuSeconds;

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The gen3 copy of the test track: same terrain, gen3 in place of gen4.
std::string Gen3TestTrack(const std::filesystem::path& dir) {
  const std::string source = std::string(SP_SOURCE_DIR) + "/models/worlds/test_track.xml";
  std::string xml = ReadFile(source);
  const std::string gen4 = "file=\"../robots/workpartner_gen4.xml\"";
  const size_t at = xml.find(gen4);
  if (at == std::string::npos) {
    std::cerr << "viewer_bench: " << source << " no longer places " << gen4 << "\n";
    std::exit(1);
  }
  xml.replace(at, gen4.size(),
              "file=\"" + std::string(SP_SOURCE_DIR) + "/models/robots/workpartner_gen3.xml\"");
  const std::filesystem::path path = dir / "test_track_gen3.xml";
  std::ofstream(path) << xml;
  return path.string();
}

// Collects the sim's real-time factor from SIM_STATUS.
class StatusWatch {
 public:
  explicit StatusWatch(const std::string& url) : lcm_(url) {
    lcm_.subscribe(simpartner::channels::kStatus, &StatusWatch::OnStatus, this);
  }
  void Pump(double seconds) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) lcm_.handleTimeout(20);
  }
  void Reset() {
    factors_.clear();
    behind_ = 0;
  }
  double MeanFactor() const {
    double sum = 0;
    for (double f : factors_) sum += f;
    return factors_.empty() ? 0 : sum / factors_.size();
  }
  int behind() const { return behind_; }
  lcm::LCM& lcm() { return lcm_; }

 private:
  void OnStatus(const lcm::ReceiveBuffer*, const std::string&, const simpartner::status_t* s) {
    if (s->run_state == simpartner::status_t::RUN_RUNNING && s->step > 0)
      factors_.push_back(s->real_time_factor);
    for (const simpartner::warning_t& w : s->warnings)
      if (w.source == "realtime" && seen_.insert(w.step).second) ++behind_;
  }
  lcm::LCM lcm_;
  std::vector<double> factors_;
  std::set<int64_t> seen_;
  int behind_ = 0;
};

struct RunFigures {
  double fps = 0;
  double viewer_cores = 0;
  double xserver_cores = 0;
  double sim_factor = 0;
  int sim_fell_behind = 0;
};

RunFigures RunViewer(const std::string& url, const std::filesystem::path& dir, int width,
                     int height, const std::string& fps, double seconds, pid_t xvfb,
                     StatusWatch* status) {
  const std::string log = (dir / ("viewer_fps" + fps + ".log")).string();
  ChildProcess viewer({std::string(SP_BINARY_DIR) + "/viewer/simpartner-viewer", "--params",
                       "/dev/null", "--lcm-url", url, "--width", std::to_string(width),
                       "--height", std::to_string(height), "--fps", fps, "--quit-after",
                       std::to_string(seconds)},
                      log);
  // Leave out the start (window, GL context, model request, first frames).
  const double warmup = 2.0;
  status->Pump(warmup);
  status->Reset();
  const double viewer_cpu0 = ProcessCpuSeconds(viewer.pid()), x_cpu0 = ProcessCpuSeconds(xvfb);
  const auto t0 = Clock::now();
  status->Pump(seconds - warmup - 0.5);
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  RunFigures f;
  f.viewer_cores = (ProcessCpuSeconds(viewer.pid()) - viewer_cpu0) / wall;
  f.xserver_cores = (ProcessCpuSeconds(xvfb) - x_cpu0) / wall;
  f.sim_factor = status->MeanFactor();
  f.sim_fell_behind = status->behind();
  if (viewer.Wait(std::chrono::seconds(30)).value_or(-1) != 0) {
    std::cerr << "viewer_bench: the viewer failed:\n" << ReadFile(log);
    std::exit(1);
  }
  // "simpartner-viewer: N frames in T s (F fps), ..."
  const std::string text = ReadFile(log);
  const size_t at = text.find(" fps), CPU");
  const size_t open = text.rfind('(', at);
  if (at == std::string::npos || open == std::string::npos) {
    std::cerr << "viewer_bench: no frame figures in the viewer's output:\n" << text;
    std::exit(1);
  }
  f.fps = std::atof(text.c_str() + open + 1);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "viewer_bench";
  spec.summary =
      "How fast simpartner-viewer draws under a private Xvfb (Mesa llvmpipe) beside a sim at\n"
      "real time (default world: the test track with gen3): frames per second, the viewer's\n"
      "and the X server's CPU, and the sim's real-time factor, uncapped and at 60 and 30 fps.";
  spec.options = {
      simpartner::Number("seconds", "S", "per run, at least 4 (default 12)"),
      simpartner::Integer("width", "W", "window width (default 1280)"),
      simpartner::Integer("height", "H", "window height (default 720)"),
  };
  spec.positionals = {simpartner::Positional{"world.xml", 0, 1}};
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const double seconds = std::max(4.0, args.Number("seconds", 12));
  const int width = static_cast<int>(args.Integer("width", 1280));
  const int height = static_cast<int>(args.Integer("height", 720));
  std::string world = args.positional().empty() ? "" : args.positional()[0];
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("sp_viewer_bench_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  if (world.empty()) world = Gen3TestTrack(dir);

  simpartner::viewer::XvfbServer xvfb(width, height, (dir / "xvfb.log").string());
  ::setenv("DISPLAY", xvfb.display().c_str(), 1);
  const int port = 40000 + static_cast<int>(::getpid()) % 20000;
  const std::string url = "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
  StatusWatch status(url);
  ChildProcess sim({std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim", "--params",
                    "/dev/null", "--environment=" + world, "--lcm-url", url, "--speed=1"},
                   (dir / "sim.log").string());
  status.Pump(1.5);

  std::cout << "viewer_bench: " << world << ", " << width << "x" << height << " under Xvfb "
            << xvfb.display() << ", sim at real time, " << seconds << " s per run, "
            << std::thread::hardware_concurrency() << " cores\n";
  std::printf("%-22s %8s %14s %14s %12s %12s\n", "viewer", "fps", "viewer cores",
              "Xvfb cores", "sim x real", "sim behind");
  for (const std::string fps : {"0", "60", "30"}) {
    const RunFigures f = RunViewer(url, dir, width, height, fps, seconds, xvfb.pid(), &status);
    std::printf("%-22s %8.1f %14.2f %14.2f %12.3f %12d\n",
                fps == "0" ? "--fps 0 (unlimited)" : fps == "60" ? "--fps 60 (default)" : "--fps 30", f.fps, f.viewer_cores,
                f.xserver_cores, f.sim_factor, f.sim_fell_behind);
    std::fflush(stdout);
  }
  // The sim alone, for comparison.
  status.Pump(1.0);
  status.Reset();
  const double sim_cpu0 = ProcessCpuSeconds(sim.pid());
  const auto t0 = Clock::now();
  status.Pump(4.0);
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("%-22s %8s %14s %14s %12.3f %12d   (sim %.2f cores)\n", "no viewer", "-", "-", "-",
              status.MeanFactor(), status.behind(), (ProcessCpuSeconds(sim.pid()) - sim_cpu0) / wall);

  simpartner::control_t quit{};
  quit.action = simpartner::control_t::ACTION_QUIT;
  quit.sender = "viewer_bench";
  // Signed as every process signs (the user's key, or SIMPARTNER_BUS_KEY).
  std::optional<simpartner::BusSigning> signing = simpartner::BusSigning::FromEnvironment(
      [](const std::string& line) { std::cerr << "viewer_bench: " << line << "\n"; });
  simpartner::PublishSigned(&status.lcm(), simpartner::channels::kControl, quit,
                            signing ? &*signing : nullptr);
  sim.Wait(std::chrono::seconds(5));
  std::filesystem::remove_all(dir);
  return 0;
}
