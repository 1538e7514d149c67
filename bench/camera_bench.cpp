// camera_bench: what simpartner-camera keeps up with on this machine, under
// a private Xvfb with Mesa's llvmpipe (software rendering), beside a
// simpartner-sim running WorkPartner gen3 at real time.
//
//   camera_bench [--seconds N] [--rate HZ] [--width W --height H] [--depth none|metres|millimetres]
//
// The gen3 of models/robots with its HeadCamera set to the size, rate and
// depth asked for (a copy in a temporary directory), in the pole task world
// (models/worlds/pole_task.xml: cubes and a pole in front of the camera).
// Prints the frames the camera rendered against the frames due (from its
// own summary), the frames this bench received on SIM_IMAGE, the latency
// from the state's publication (right after its step) to the image's
// publication (the camera's figure) and to its arrival here, the CPU of
// the camera, the X server and the sim as fractions of a core, and the
// sim's real-time factor over the run (from its last line).
#include <lcm/lcm-cpp.hpp>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "process_cpu.h"
#include "simpartner/bounded_file.h"
#include "simpartner/bus_decode.h"
#include "simpartner/bus_url.h"
#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_line.h"
#include "simpartner/image_t.hpp"
#include "simpartner/sender.h"
#include "simpartner/state_t.hpp"
#include "simpartner/viewer/xvfb.h"
#include "simpartner/bus_signing.h"

namespace {

using Clock = std::chrono::steady_clock;
using simpartner::ChildProcess;
using simpartner::bench::ProcessCpuSeconds;

constexpr size_t kMaxLogBytes = 64 << 20;

std::string Read(const std::filesystem::path& path) {
  return simpartner::ReadBoundedFile(path.string(), kMaxLogBytes, "logs");
}

// Replaces the first `from` after `anchor` in `text` by `to`, or exits
// saying the shipped file changed.
void ReplaceAfter(std::string* text, const std::string& anchor, const std::string& from,
                  const std::string& to) {
  const size_t at = text->find(anchor);
  const size_t found = at == std::string::npos ? at : text->find(from, at);
  if (found == std::string::npos) {
    std::cerr << "camera_bench: the shipped gen3 no longer has '" << from << "' after '" << anchor
              << "'\n";
    std::exit(1);
  }
  text->replace(found, from.size(), to);
}

// The shipped gen3 with its HeadCamera as asked.
std::string Gen3WithCamera(const std::filesystem::path& dir, int width, int height, double rate,
                           const std::string& depth) {
  std::string xml = Read(std::string(SP_SOURCE_DIR) + "/models/robots/workpartner_gen3.xml");
  const std::string camera = "name=\"HeadCamera\"";
  ReplaceAfter(&xml, camera, "<rate>15</rate>", "<rate>" + std::to_string(rate) + "</rate>");
  ReplaceAfter(&xml, camera, ">640<", ">" + std::to_string(width) + "<");
  ReplaceAfter(&xml, camera, ">480<", ">" + std::to_string(height) + "<");
  ReplaceAfter(&xml, camera, ">millimetres<", ">" + depth + "<");
  const std::filesystem::path path = dir / "workpartner_gen3_camera.xml";
  std::ofstream(path) << xml;
  return path.string();
}

// The images on the bus: how many came, and how late after the state they
// show was published (SIM_STATE's utime, by step).
class ImageWatch {
 public:
  explicit ImageWatch(const std::string& url) : lcm_(url) {
    lcm_.subscribe(simpartner::channels::kImage, &ImageWatch::OnImage, this);
    lcm_.subscribe(simpartner::channels::kState, &ImageWatch::OnState, this);
  }
  void Pump(double seconds) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) lcm_.handleTimeout(20);
  }
  int colour() const { return colour_; }
  int depth() const { return depth_; }
  // [ms] from the state's publication to the image's arrival, per colour image.
  const std::vector<double>& latencies() const { return latencies_; }

 private:
  void OnState(const lcm::ReceiveBuffer* buffer, const std::string&) {
    simpartner::state_t state;
    if (!simpartner::DecodeLcm(buffer->data,
                               simpartner::UnsignedSize(buffer->data, buffer->data_size), &state))
      state_utime_[state.step] = state.utime;
  }
  void OnImage(const lcm::ReceiveBuffer*, const std::string&, const simpartner::image_t* image) {
    if (image->format != simpartner::image_t::FORMAT_RGB8) {
      ++depth_;
      return;
    }
    ++colour_;
    const auto it = state_utime_.find(image->step);
    if (it != state_utime_.end())
      latencies_.push_back((simpartner::WallMicros() - it->second) / 1000.0);
  }
  lcm::LCM lcm_;
  int colour_ = 0;
  int depth_ = 0;
  std::vector<double> latencies_;
  std::map<int64_t, int64_t> state_utime_;
};

// "N frames rendered of M due; latency mean X ms, max Y ms" of the camera's summary.
struct CameraFigures {
  long rendered = 0, due = 0;
  double mean_ms = 0, max_ms = 0;
};

CameraFigures ParseSummary(const std::string& log) {
  CameraFigures f;
  const size_t at = log.rfind(" frames rendered of ");
  const size_t line = log.rfind(": ", at);
  if (at == std::string::npos || line == std::string::npos ||
      std::sscanf(log.c_str() + line + 2, "%ld frames rendered of %ld due; latency mean %lf ms, max %lf",
                  &f.rendered, &f.due, &f.mean_ms, &f.max_ms) != 4) {
    std::cerr << "camera_bench: no frame figures in the camera's output:\n" << log;
    std::exit(1);
  }
  return f;
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(p * (v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "camera_bench";
  spec.summary =
      "What simpartner-camera keeps up with under a private Xvfb (Mesa llvmpipe) beside a sim\n"
      "running WorkPartner gen3 at real time: frames rendered against frames due, frames\n"
      "received, latency from a state to its image, and the CPU of each process.";
  spec.options = {
      simpartner::Number("seconds", "S", "sim time of the run, at least 4 (default 20)"),
      simpartner::Number("rate", "HZ", "camera frames a second of sim time (default 30)")
          .Range(1, 1000),
      simpartner::Integer("width", "W", "image width (default 640)").Range(16, 4096),
      simpartner::Integer("height", "H", "image height (default 480)").Range(16, 4096),
      simpartner::Text("depth", "KIND", "depth image: none, metres or millimetres (default metres)")
          .Choices({"none", "metres", "millimetres"}),
  };
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const double seconds = std::max(4.0, args.Number("seconds", 20));
  const double rate = args.Number("rate", 30);
  const int width = static_cast<int>(args.Integer("width", 640));
  const int height = static_cast<int>(args.Integer("height", 480));
  const std::string depth = args.Text("depth", "metres");
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("sp_camera_bench_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string robot = Gen3WithCamera(dir, width, height, rate, depth);

  simpartner::viewer::XvfbServer xvfb(640, 480, (dir / "xvfb.log").string());
  const std::string url = simpartner::PrivateBusUrl(::getpid(), 0);
  ImageWatch images(url);

  ::setenv("DISPLAY", xvfb.display().c_str(), 1);
  ChildProcess camera({std::string(SP_BINARY_DIR) + "/camera/simpartner-camera", "--params",
                       "/dev/null", "--lcm-url", url},
                      (dir / "camera.log").string());
  images.Pump(1.0);  // the camera's window and GL context
  ChildProcess sim({std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim", "--params",
                    "/dev/null", "--environment=" + std::string(SP_SOURCE_DIR) +
                                     "/models/worlds/pole_task.xml",
                    "--robot", robot, "--lcm-url", url, "--speed=1",
                    "--duration=" + std::to_string(seconds)},
                   (dir / "sim.log").string());
  std::cout << "camera_bench: gen3 HeadCamera " << width << "x" << height << " RGB"
            << (depth == "none" ? "" : " + depth (" + depth + ")") << " at " << rate
            << " Hz of sim time, sim at real time for " << seconds << " s, Xvfb "
            << xvfb.display() << ", " << std::thread::hardware_concurrency() << " cores\n";
  const double camera_cpu0 = ProcessCpuSeconds(camera.pid()), x_cpu0 = ProcessCpuSeconds(xvfb.pid());
  const auto t0 = Clock::now();
  double sim_cpu = 0;
  while (!sim.Wait(std::chrono::milliseconds(0))) {
    sim_cpu = std::max(sim_cpu, ProcessCpuSeconds(sim.pid()));
    images.Pump(0.2);
  }
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const double camera_cores = (ProcessCpuSeconds(camera.pid()) - camera_cpu0) / wall;
  const double x_cores = (ProcessCpuSeconds(xvfb.pid()) - x_cpu0) / wall;
  images.Pump(1.0);  // the last images
  camera.Signal(SIGTERM);
  camera.Wait(std::chrono::seconds(10));
  const CameraFigures f = ParseSummary(Read(dir / "camera.log"));
  const std::string sim_log = Read(dir / "sim.log");
  const size_t factor_at = sim_log.rfind(" x real time overall");
  const size_t factor_open = sim_log.rfind('(', factor_at);
  const double factor = factor_at == std::string::npos || factor_open == std::string::npos
                            ? 0
                            : std::atof(sim_log.c_str() + factor_open + 1);

  std::printf("frames due %ld, rendered %ld (%.1f %%), received on SIM_IMAGE %d colour + %d depth\n",
              f.due, f.rendered, 100.0 * f.rendered / std::max(f.due, 1L), images.colour(),
              images.depth());
  std::printf("latency state -> image published: mean %.1f ms, max %.1f ms (the camera's figures)\n",
              f.mean_ms, f.max_ms);
  std::printf("latency state -> image received here: median %.1f ms, 95th %.1f ms, max %.1f ms\n",
              Percentile(images.latencies(), 0.5), Percentile(images.latencies(), 0.95),
              Percentile(images.latencies(), 1.0));
  std::printf("CPU: camera %.2f cores, Xvfb %.2f cores, sim %.2f cores; sim %.3f x real time\n",
              camera_cores, x_cores, sim_cpu / wall, factor);
  std::filesystem::remove_all(dir);
  return 0;
}
