#include "simpartner/viewer/app.h"

#include <SDL2/SDL.h>
#include <SDL2/SDL_opengl.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstring>

#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "simpartner/control_t.hpp"
#include "simpartner/viewer/bus.h"
#include "simpartner/viewer/camera_images.h"
#include "simpartner/viewer/gl_window.h"
#include "simpartner/viewer/hud_text.h"
#include "simpartner/viewer/keys.h"
#include "simpartner/viewer/line_of_sight.h"
#include "simpartner/viewer/renderer.h"
#include "simpartner/viewer/scene.h"

namespace simpartner::viewer {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kOrbitRadiansPerPixel = 0.006;
constexpr double kZoomPerWheelStep = 0.9;
constexpr double kFlySpeedPerDistance = 0.8;  // [1/s]: flies 0.8 x the camera distance per second
constexpr double kFastFlyFactor = 4.0;
constexpr double kWarningSeconds = 10.0;  // [s of sim time] a warning stays on the HUD
constexpr Color3 kWhite{1, 1, 1};

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

double ProcessCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

class Viewer {
 public:
  Viewer(const ViewerOptions& options, std::ostream& out, std::ostream& err)
      : options_(options),
        out_(out),
        err_(err),
        toggles_(options.toggles),
        window_("SimPartner viewer", options.width, options.height, options.max_fps > 0),
        lcm_(OpenLcm(options.lcm_url)),
        signing_(BusSigning::FromEnvironment(
            [&err](const std::string& line) { err << "simpartner-viewer: " << line << std::endl; })),
        bus_(lcm_.get(), options.lcm_url, &scene_, [this](const std::string& m) { Warn(m); },
             signing_ ? &*signing_ : nullptr),
        images_(lcm_.get(), signing_ ? &*signing_ : nullptr,
                [this](const std::string& m) { Warn(m); }, options.camera_image) {
    out_ << "simpartner-viewer: OpenGL " << Text(GL_VERSION) << " on " << Text(GL_RENDERER)
         << ", listening on " << bus_.url() << std::endl;
    renderer_ = std::make_unique<Renderer>();
    if (options_.camera) camera_ = CameraFromSpec(*options_.camera, scene_.Up());
  }

  int Run() {
    start_ = Clock::now();
    const double cpu_at_start = ProcessCpuSeconds();
    bus_.RequestModelIfNeeded();  // a late viewer need not wait for the periodic announcement
    Clock::time_point last_frame = start_;
    Clock::time_point last_draw = start_;
    Clock::time_point next_poll = start_;
    while (!quit_) {
      const Clock::time_point frame_start = Clock::now();
      if (options_.quit_after > 0 && Seconds(frame_start - start_) >= options_.quit_after) break;
      const double dt = std::min(Seconds(frame_start - last_frame), 0.1);
      last_frame = frame_start;

      SDL_Event event;
      while (SDL_PollEvent(&event)) {
        HandleEvent(event);
        dirty_ = true;  // input, exposure, resizing: draw again
      }
      bus_.Drain(frame_start);  // everything that arrived; keeps only the newest state
      bus_.RequestModelIfNeeded();
      FollowModel();
      Fly(dt);
      if (toggles_.follow)
        if (auto centre = scene_.FollowPoint()) camera_.target = *centre;
      if (options_.scanner_poll_hz > 0 && frame_start >= next_poll) {
        bus_.RequestScans();
        next_poll = frame_start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(1.0 / options_.scanner_poll_hz));
      }

      if (scene_.has_model())
        images_.Judge(scene_.model(), scene_.state() ? scene_.state()->step : -1);
      // Nothing new (a paused or stopped sim, no input): keep the picture
      // and spend no CPU on it, but refresh the HUD once a second. Frame
      // counts (--fps 0, --frames) draw every frame.
      const bool every_frame = options_.max_fps == 0 || options_.after_frames > 0;
      const bool redraw = dirty_ || every_frame || !held_.empty() ||
                          scene_.version() != drawn_version_ ||
                          images_.version() != drawn_images_version_ || ScreenshotDue(frame_start) ||
                          pending_key_screenshot_ || frame_start - last_draw >= std::chrono::seconds(1);
      if (!redraw) {
        WaitForNextFrame(frame_start);
        continue;
      }
      dirty_ = false;
      drawn_version_ = scene_.version();
      drawn_images_version_ = images_.version();
      last_draw = frame_start;
      const auto [width, height] = window_.DrawableSize();
      // Following, a wall between the robot and the eye is looked past.
      const Camera drawn = toggles_.follow ? UnblockedCamera(camera_, scene_) : camera_;
      renderer_->Draw(scene_, drawn, toggles_, MakeHud(), width, height);
      ++frames_;
      UpdateFps(frame_start);
      if (ScreenshotDue(frame_start)) {
        const int status = WriteScreenshot(options_.screenshot, width, height) ? 0 : 1;
        PrintSummary(cpu_at_start);
        return status;
      }
      if (pending_key_screenshot_) {
        pending_key_screenshot_ = false;
        WriteScreenshot(KeyScreenshotName(), width, height);
      }
      SDL_GL_SwapWindow(window_.get());
      WaitForNextFrame(frame_start);
    }
    PrintSummary(cpu_at_start);
    return 0;
  }

 private:
  static std::unique_ptr<lcm::LCM> OpenLcm(const std::string& url) {
    auto lcm = std::make_unique<lcm::LCM>(url);
    if (!lcm->good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
    return lcm;
  }

  static std::string Text(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s != nullptr ? reinterpret_cast<const char*>(s) : "?";
  }

  // Waits for the next frame on the bus, so messages are handled as they
  // come instead of piling up in the socket.
  void WaitForNextFrame(Clock::time_point frame_start) {
    if (options_.max_fps <= 0) return;
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(1.0 / options_.max_fps));
    bus_.Drain(frame_start + period);
  }

  void Warn(const std::string& message) { err_ << "simpartner-viewer: " << message << std::endl; }

  // A new model (first one or a restarted sim): frame it, say so.
  void FollowModel() {
    if (scene_.model_generation() == seen_generation_) return;
    seen_generation_ = scene_.model_generation();
    const model_t& m = scene_.model();
    std::string robots;
    for (const robot_t& r : m.robots) robots += (robots.empty() ? "" : ", ") + r.model;
    out_ << "simpartner-viewer: model of simulation " << m.simulation_id << ": world '"
         << m.world_name << "'" << (robots.empty() ? "" : " with " + robots) << ", "
         << m.num_bodies << " bodies, " << m.num_joints << " joints, " << m.num_sensors
         << " sensors" << (m.heightfield.present ? ", heightfield" : "")
         << (m.has_plane ? ", plane" : "") << std::endl;
    ResetCamera();
  }

  void ResetCamera() {
    if (options_.camera) {
      camera_ = CameraFromSpec(*options_.camera, scene_.Up());
      return;
    }
    const auto [centre, radius] = scene_.FocusSphere();
    camera_ = FramingCamera(scene_.Up(), centre, radius);
    toggles_.follow = options_.toggles.follow && scene_.FollowPoint().has_value();
  }

  void HandleEvent(const SDL_Event& e) {
    switch (e.type) {
      case SDL_QUIT: quit_ = true; break;
      case SDL_KEYDOWN: {
        const KeyAction action = ActionForKey(e.key.keysym.sym);
        if (IsFlyAction(action)) {
          held_.insert(action);
          toggles_.follow = false;
        } else if (e.key.repeat == 0) {
          OnKey(action);
        }
        break;
      }
      case SDL_KEYUP: held_.erase(ActionForKey(e.key.keysym.sym)); break;
      case SDL_MOUSEMOTION: {
        const bool shift = (SDL_GetModState() & KMOD_SHIFT) != 0;
        const bool left = (e.motion.state & SDL_BUTTON_LMASK) != 0;
        const bool pan = (e.motion.state & (SDL_BUTTON_RMASK | SDL_BUTTON_MMASK)) != 0 ||
                         (left && shift);
        if (pan) {
          camera_.Pan(e.motion.xrel, e.motion.yrel, window_.DrawableSize().second);
          toggles_.follow = false;
        } else if (left) {
          camera_.Orbit(-e.motion.xrel * kOrbitRadiansPerPixel,
                        e.motion.yrel * kOrbitRadiansPerPixel);
        }
        break;
      }
      case SDL_MOUSEWHEEL:
        camera_.Zoom(std::pow(kZoomPerWheelStep, e.wheel.y));
        break;
      default: break;
    }
  }

  void OnKey(KeyAction action) {
    switch (action) {
      case KeyAction::kQuit: quit_ = true; break;
      case KeyAction::kToggleHelp: toggles_.key_help = !toggles_.key_help; break;
      case KeyAction::kTogglePause: {
        const status_t* s = scene_.status();
        const bool paused = s != nullptr && (s->run_state == status_t::RUN_PAUSED ||
                                             s->run_state == status_t::RUN_FAULTED);
        bus_.SendControl(paused ? control_t::ACTION_RESUME : control_t::ACTION_PAUSE);
        break;
      }
      case KeyAction::kStep: bus_.SendControl(control_t::ACTION_STEP, 1); break;
      case KeyAction::kStep100: bus_.SendControl(control_t::ACTION_STEP, 100); break;
      case KeyAction::kReset: bus_.SendControl(control_t::ACTION_RESET); break;
      case KeyAction::kToggleWireframe: toggles_.wireframe = !toggles_.wireframe; break;
      case KeyAction::kToggleFrames: toggles_.body_frames = !toggles_.body_frames; break;
      case KeyAction::kToggleContactForces:
        toggles_.contact_forces = !toggles_.contact_forces;
        break;
      case KeyAction::kToggleJointForces: toggles_.joint_forces = !toggles_.joint_forces; break;
      case KeyAction::kToggleScannerRays: toggles_.scanner_rays = !toggles_.scanner_rays; break;
      case KeyAction::kToggleGrid: toggles_.grid = !toggles_.grid; break;
      case KeyAction::kToggleHud: toggles_.hud = !toggles_.hud; break;
      case KeyAction::kToggleFollow: toggles_.follow = !toggles_.follow; break;
      case KeyAction::kResetCamera: ResetCamera(); break;
      case KeyAction::kScreenshot: pending_key_screenshot_ = true; break;
      case KeyAction::kNextCameraImage:
        if (scene_.has_model()) images_.ShowNext(scene_.model());
        break;
      default: break;
    }
  }

  void Fly(double dt) {
    if (held_.empty()) return;
    double forward = 0, left = 0, rise = 0;
    for (KeyAction a : held_) {
      if (a == KeyAction::kFlyForward) forward += 1;
      if (a == KeyAction::kFlyBack) forward -= 1;
      if (a == KeyAction::kFlyLeft) left += 1;
      if (a == KeyAction::kFlyRight) left -= 1;
      if (a == KeyAction::kFlyUp) rise += 1;
      if (a == KeyAction::kFlyDown) rise -= 1;
    }
    double speed = kFlySpeedPerDistance * camera_.distance * dt;
    if (SDL_GetModState() & KMOD_SHIFT) speed *= kFastFlyFactor;
    camera_.Fly(forward * speed, left * speed, rise * speed);
  }

  Hud MakeHud() const {
    Hud hud;
    if (toggles_.key_help) {
      hud.key_help = KeyHelpLines();
      hud.key_help.insert(hud.key_help.begin(), {"SimPartner viewer: keys", ""});
    }
    if (const image_t* image = images_.Newest(scene_.simulation_id()))
      hud.inset = Inset{image->width, image->height, image->data.data(),
                        "camera " + image->name + ", step " + std::to_string(image->step)};
    if (!toggles_.hud) return hud;
    if (!scene_.has_model()) {
      hud.top.push_back({"waiting for SIM_MODEL on " + bus_.url() + " (asked " +
                             std::to_string(bus_.model_requests()) + " times)",
                         kWhite});
    } else {
      const model_t& m = scene_.model();
      const state_t* s = scene_.state();
      const status_t* st = scene_.status();
      const std::string line = SimLine(m, s, st);
      const bool alarm = st != nullptr && st->run_state == status_t::RUN_FAULTED;
      hud.top.push_back({line, alarm ? Color3{1.0f, 0.45f, 0.35f} : kWhite});
      if (st != nullptr) {
        // The newest two warnings of the sim from the last 10 s of sim time
        // (SIM_STATUS repeats its recent warnings for good).
        const int64_t now_step = s != nullptr ? s->step : st->step;
        const int64_t recent = m.step_size > 0 ? static_cast<int64_t>(kWarningSeconds / m.step_size) : 0;
        std::vector<const warning_t*> shown;
        for (const warning_t& w : st->warnings)
          if (w.step >= now_step - recent && w.step <= now_step) shown.push_back(&w);
        const size_t n = shown.size();
        for (size_t k = n > 2 ? n - 2 : 0; k < n; ++k) {
          const warning_t& w = *shown[k];
          std::string text = "step " + std::to_string(w.step) + " " + w.source + ": " + w.message;
          if (!w.bodies.empty()) {
            text += " (";
            for (size_t b = 0; b < w.bodies.size(); ++b) text += (b ? ", " : "") + w.bodies[b];
            text += ")";
          }
          hud.top.push_back({Clip(text), w.severity == warning_t::SEVERITY_ERROR
                                             ? Color3{1.0f, 0.45f, 0.35f}
                                             : Color3{1.0f, 0.85f, 0.3f}});
        }
      }
    }
    if (scene_.rejected_total() > 0) {
      hud.top.push_back({Clip("viewer ignored: " + scene_.RejectionSummary()), {1.0f, 0.6f, 0.2f}});
      hud.top.push_back({Clip("  last: " + scene_.recent_problems().back().message),
                         {1.0f, 0.6f, 0.2f}});
    }
    std::string hint = "h: keys   " + Fixed(fps_, 0) + " fps";
    if (toggles_.follow && scene_.FollowPoint())
      hint += scene_.has_model() && scene_.model().num_robots > 0 ? "   following the robot"
                                                                  : "   following what moves";
    if (toggles_.wireframe) hint += "   wireframe";
    hud.bottom.push_back({hint, {0.85f, 0.9f, 1.0f}});
    return hud;
  }

  static std::string Clip(const std::string& text) {
    constexpr size_t kMax = 100;
    return text.size() <= kMax ? text : text.substr(0, kMax - 3) + "...";
  }

  void UpdateFps(Clock::time_point now) {
    ++fps_frames_;
    const double window = Seconds(now - fps_window_start_);
    if (window >= 1.0) {
      fps_ = fps_frames_ / window;
      fps_frames_ = 0;
      fps_window_start_ = now;
    }
  }

  bool ScreenshotDue(Clock::time_point now) const {
    if (options_.screenshot.empty()) return false;
    if (options_.after_frames > 0) return frames_ >= options_.after_frames;
    return Seconds(now - start_) >= options_.after_seconds;
  }

  static std::string KeyScreenshotName() {
    const std::time_t t = std::time(nullptr);
    std::tm local{};
    localtime_r(&t, &local);
    char name[64];
    std::strftime(name, sizeof name, "viewer-%Y%m%d-%H%M%S.png", &local);
    return name;
  }

  bool WriteScreenshot(const std::string& path, int width, int height) {
    try {
      WritePng(path, renderer_->ReadPixels(width, height));
    } catch (const PngError& e) {
      Warn(std::string("screenshot not written: ") + e.what());
      return false;
    }
    std::ostringstream what;
    what << "simpartner-viewer: screenshot " << path << " (" << width << "x" << height;
    if (scene_.has_model()) {
      what << ", simulation " << scene_.simulation_id() << ", "
           << (scene_.state() != nullptr ? "step " + std::to_string(scene_.state()->step)
                                         : std::string("no state yet"))
           << ", " << renderer_->bodies_drawn() << " bodies drawn";
    } else {
      what << ", no model yet";
    }
    out_ << what.str() << ")" << std::endl;
    return true;
  }

  // At the end: what has already arrived is still handled, so that the
  // summary counts every message that came before the viewer was told to
  // end (a quit key or signal is handled before the frame's messages).
  void PrintSummary(double cpu_at_start) {
    bus_.Drain(Clock::now());
    const double seconds = Seconds(Clock::now() - start_);
    const double cpu = ProcessCpuSeconds() - cpu_at_start;
    out_ << "simpartner-viewer: " << frames_ << " frames in " << Fixed(seconds, 2) << " s ("
         << Fixed(frames_ / std::max(seconds, 1e-9), 1) << " fps), CPU " << Fixed(cpu, 2)
         << " s; states accepted " << scene_.states_accepted() << ", model requests "
         << bus_.model_requests() << "; ignored: "
         << (scene_.rejected_total() == 0 ? "none" : scene_.RejectionSummary()) << std::endl;
  }

  ViewerOptions options_;
  std::ostream& out_;
  std::ostream& err_;
  Toggles toggles_;
  GlWindow window_;
  Scene scene_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::optional<BusSigning> signing_;  // SIMPARTNER_BUS_KEY
  ViewerBus bus_;
  CameraImages images_;  // the inset's camera image
  std::unique_ptr<Renderer> renderer_;
  Camera camera_;
  int64_t seen_generation_ = 0;
  std::set<KeyAction> held_;
  bool quit_ = false;
  bool dirty_ = true;
  int64_t drawn_version_ = -1;
  int64_t drawn_images_version_ = -1;
  bool pending_key_screenshot_ = false;
  Clock::time_point start_;
  int64_t frames_ = 0;
  int64_t fps_frames_ = 0;
  Clock::time_point fps_window_start_ = Clock::now();
  double fps_ = 0;
};

}  // namespace

int RunViewer(const ViewerOptions& options, std::ostream& out, std::ostream& err) {
  // Before any thread starts: Linux priorities are per thread and the
  // renderer's threads (llvmpipe's) inherit this one's.
  if (options.nice > 0) {
    errno = 0;
    const int current = getpriority(PRIO_PROCESS, 0);
    if (errno == 0 && setpriority(PRIO_PROCESS, 0, std::min(current + options.nice, 19)) != 0)
      err << "simpartner-viewer: cannot lower the priority by " << options.nice << ": "
          << std::strerror(errno) << std::endl;
  }
  Viewer viewer(options, out, err);
  return viewer.Run();
}

}  // namespace simpartner::viewer
