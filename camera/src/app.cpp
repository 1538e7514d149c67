#include "simpartner/camera/app.h"

#include <SDL2/SDL_opengl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "simpartner/bus_signing.h"
#include "simpartner/bus_url.h"
#include "simpartner/camera/camera_sensor.h"
#include "simpartner/camera/offscreen.h"
#include "simpartner/channels.h"
#include "simpartner/image_t.hpp"
#include "simpartner/sender.h"
#include "simpartner/stop_signals.h"
#include "simpartner/text.h"
#include "simpartner/viewer/bus.h"
#include "simpartner/viewer/gl_window.h"
#include "simpartner/png_image.h"
#include "simpartner/viewer/scene.h"

namespace simpartner::camera {
namespace {

using Clock = std::chrono::steady_clock;

// A camera's name as a file name: the name comes from the bus, so
// anything but letters, digits, '-' and '_' (a '/', a leading '.')
// becomes '_'.
std::string SafeFileName(std::string name) {
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '_';
  return name;
}

// What one camera has done since its model came.
struct CameraRun {
  explicit CameraRun(const CameraSensor& c) : sensor(c), schedule(c.period_steps) {}
  CameraSensor sensor;
  FrameSchedule schedule;
  int64_t rendered = 0;
  double latency_sum_ms = 0;  // state published to image published
  double latency_max_ms = 0;
  RgbImage last;
};

class CameraProcess {
 public:
  CameraProcess(const CameraOptions& options, std::ostream& out, std::ostream& err)
      : options_(options),
        out_(out),
        err_(err),
        stop_fd_(BlockStopSignalsIntoFd()),
        window_("simpartner-camera", 64, 64, false, true),
        lcm_(OpenLcm(options.lcm_url)),
        signing_(BusSigning::FromEnvironment(
            [&err](const std::string& line) { err << "simpartner-camera: " << line << std::endl; })),
        bus_(lcm_.get(), options.lcm_url, &scene_, [this](const std::string& m) { Warn(m); },
             signing_ ? &*signing_ : nullptr, "camera") {
    bus_.SetStateListener([this](const state_t& state) { OnState(state); });
    out_ << "simpartner-camera: OpenGL " << GlText(GL_VERSION) << " on " << GlText(GL_RENDERER)
         << " (images up to " << offscreen_.max_side() << " pixels a side), listening on "
         << bus_.url() << std::endl;
  }
  ~CameraProcess() {
    if (stop_fd_ >= 0) ::close(stop_fd_);
  }
  CameraProcess(const CameraProcess&) = delete;
  CameraProcess& operator=(const CameraProcess&) = delete;

  int Run() {
    const Clock::time_point start = Clock::now();
    bus_.RequestModelIfNeeded();  // a late camera need not wait for the periodic announcement
    while (!StopRequested()) {
      const Clock::time_point now = Clock::now();
      if (options_.quit_after > 0 &&
          std::chrono::duration<double>(now - start).count() >= options_.quit_after)
        break;
      SDL_PumpEvents();  // the hidden window's X events, so none pile up
      bus_.Drain(now + std::chrono::milliseconds(50));
      bus_.RequestModelIfNeeded();
      FollowModel();  // a model without states yet (a paused sim) is announced too
    }
    PrintSummary();
    SaveFrames();
    return 0;
  }

 private:
  // With the large receive buffer (bus_url.h): every state can be due, and
  // the socket also hears the images, its own and other cameras'.
  static std::unique_ptr<lcm::LCM> OpenLcm(const std::string& url) {
    auto lcm = std::make_unique<lcm::LCM>(WithReceiveBuffer(url));
    if (!lcm->good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
    return lcm;
  }

  static std::string GlText(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s != nullptr ? reinterpret_cast<const char*>(s) : "?";
  }

  bool StopRequested() const {
    if (stop_fd_ < 0) return false;
    pollfd p{stop_fd_, POLLIN, 0};
    return ::poll(&p, 1, 0) > 0;
  }

  void Warn(const std::string& message) { err_ << "simpartner-camera: " << message << std::endl; }

  // A new model (the first, or a restarted sim): its cameras, from scratch.
  void FollowModel() {
    if (!scene_.has_model() || scene_.model_generation() == seen_generation_) return;
    seen_generation_ = scene_.model_generation();
    if (!cameras_.empty()) PrintSummary();
    cameras_.clear();
    cameras_simulation_ = scene_.simulation_id();
    std::vector<std::string> problems;
    for (CameraSensor& c : CamerasOfModel(scene_.model(), &problems)) {
      if (std::max(c.width, c.height) > offscreen_.max_side()) {
        problems.push_back("SIM_MODEL: camera '" + c.name + "' is " + std::to_string(c.width) +
                           "x" + std::to_string(c.height) + ", more than the " +
                           std::to_string(offscreen_.max_side()) +
                           " pixels a side this OpenGL driver renders; not rendered");
        continue;
      }
      cameras_.emplace_back(c);
    }
    for (const std::string& p : problems) Warn(p);
    out_ << "simpartner-camera: simulation " << scene_.simulation_id() << ": " << cameras_.size()
         << " camera" << (cameras_.size() == 1 ? "" : "s");
    for (const CameraRun& c : cameras_)
      out_ << (&c == &cameras_.front() ? ": " : ", ") << c.sensor.name << " " << c.sensor.width
           << "x" << c.sensor.height << " at " << ShortestNumber(c.sensor.rate) << " Hz";
    out_ << std::endl;
  }

  void OnState(const state_t& state) {
    FollowModel();
    for (CameraRun& camera : cameras_)
      if (camera.schedule.Due(state.step)) RenderAndPublish(state, &camera);
  }

  void RenderAndPublish(const state_t& state, CameraRun* camera) {
    const CameraSensor& c = camera->sensor;
    Frame frame = offscreen_.Render(scene_, c);
    image_t image{};
    image.simulation_id = state.simulation_id;
    image.step = state.step;
    image.sim_time = state.sim_time;
    image.camera = c.index;
    image.name = c.name;
    image.robot = c.robot;
    image.width = c.width;
    image.height = c.height;
    image.format = image_t::FORMAT_RGB8;
    image.data = frame.rgb.pixels;
    image.num_bytes = static_cast<int32_t>(image.data.size());
    image.utime = WallMicros();
    PublishSigned(lcm_.get(), channels::kImage, image, signing_ ? &*signing_ : nullptr);
    if (c.depth != DepthFormat::kNone) {
      image.format = c.depth == DepthFormat::kMetres ? image_t::FORMAT_DEPTH_F32
                                                     : image_t::FORMAT_DEPTH_U16;
      image.data = DepthBytes(frame.depth_buffer, c);
      image.num_bytes = static_cast<int32_t>(image.data.size());
      image.utime = WallMicros();
      PublishSigned(lcm_.get(), channels::kImage, image, signing_ ? &*signing_ : nullptr);
    }
    const double latency_ms = (image.utime - state.utime) / 1000.0;
    ++camera->rendered;
    camera->latency_sum_ms += latency_ms;
    camera->latency_max_ms = std::max(camera->latency_max_ms, latency_ms);
    camera->last = std::move(frame.rgb);
  }

  void PrintSummary() {
    for (const CameraRun& c : cameras_) {
      out_ << "simpartner-camera: camera '" << c.sensor.name << "' of simulation "
           << cameras_simulation_ << ": " << c.rendered << " frames rendered of "
           << c.schedule.due() << " due; latency mean "
           << FormatFixed(c.rendered > 0 ? c.latency_sum_ms / c.rendered : 0, 1) << " ms, max "
           << FormatFixed(c.latency_max_ms, 1) << " ms" << std::endl;
    }
    out_ << "simpartner-camera: states accepted " << scene_.states_accepted()
         << ", model requests " << bus_.model_requests() << "; ignored: "
         << (scene_.rejected_total() == 0 ? "none" : scene_.RejectionSummary()) << std::endl;
  }

  void SaveFrames() {
    if (options_.save_dir.empty()) return;
    std::filesystem::create_directories(options_.save_dir);
    for (const CameraRun& c : cameras_) {
      if (c.last.pixels.empty()) continue;
      const std::string path = options_.save_dir + "/" + SafeFileName(c.sensor.name) + ".png";
      try {
        WritePng(path, c.last);
        out_ << "simpartner-camera: wrote " << path << std::endl;
      } catch (const PngError& e) {
        Warn(std::string("frame not written: ") + e.what());
      }
    }
  }

  CameraOptions options_;
  std::ostream& out_;
  std::ostream& err_;
  int stop_fd_;
  viewer::GlWindow window_;
  OffscreenRenderer offscreen_;
  viewer::Scene scene_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::optional<BusSigning> signing_;  // SIMPARTNER_BUS_KEY
  viewer::ViewerBus bus_;
  int64_t seen_generation_ = 0;
  std::vector<CameraRun> cameras_;
  int64_t cameras_simulation_ = 0;  // the simulation cameras_ belong to
};

}  // namespace

int RunCamera(const CameraOptions& options, std::ostream& out, std::ostream& err) {
  // Stop signals come through the loop (stop_signals.h), not SDL's handler.
  SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
  CameraProcess camera(options, out, err);
  return camera.Run();
}

}  // namespace simpartner::camera
