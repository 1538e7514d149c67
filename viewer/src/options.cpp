#include "simpartner/viewer/options.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "simpartner/bus_url.h"
#include "simpartner/viewer/keys.h"

namespace simpartner::viewer {
namespace {

constexpr const char* kCommandLine = "command line";

// Parses a number of flag `flag` within [lo, hi]; adds a diagnostic naming
// the flag and value otherwise.
std::optional<double> NumberInRange(const std::string& flag, const std::string& text, double lo, double hi,
                             DiagnosticList* diagnostics) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value) || value < lo || value > hi) {
    std::ostringstream range;
    range << "a number from " << lo << " to " << hi;
    diagnostics->Add(kCommandLine, 0, "--" + flag, "value '" + text + "' is not " + range.str());
    return std::nullopt;
  }
  return value;
}

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

// The names --show and --hide take.
bool* ToggleByName(Toggles* t, const std::string& name) {
  if (name == "wireframe") return &t->wireframe;
  if (name == "frames") return &t->body_frames;
  if (name == "contacts") return &t->contact_forces;
  if (name == "joints") return &t->joint_forces;
  if (name == "rays") return &t->scanner_rays;
  if (name == "grid") return &t->grid;
  if (name == "hud") return &t->hud;
  if (name == "keys") return &t->key_help;
  if (name == "follow") return &t->follow;
  return nullptr;
}
constexpr const char* kToggleNames = "wireframe, frames, contacts, joints, rays, grid, hud, keys, follow";

// The --help text before the options: what it shows, and its keys.
std::string ViewerSummary() {
  std::string keys;
  for (const std::string& line : KeyHelpLines()) keys += "  " + line + "\n";
  return "Shows whatever simulation runs on the bus in 3D. It learns the model from SIM_MODEL\n"
         "(asking with SIM_MODEL_REQUEST when it starts late or the sim restarts), draws the\n"
         "newest SIM_STATE at the display's pace, scanner rays from SIM_SENSOR and a HUD from\n"
         "SIM_STATUS. Messages that do not fit the model are counted and ignored.\n\nKeys:\n" +
         keys;
}

}  // namespace

CommandLineSpec ViewerCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-viewer";
  spec.summary = ViewerSummary();
  spec.options = {
      Number("width", "PIXELS", "window width in pixels (default 1280)").Range(64, 16384),
      Number("height", "PIXELS", "window height in pixels (default 720)").Range(64, 16384),
      Number("fps", "N", "most frames per second (default 60; 0 = as fast as it can draw)")
          .Range(0, 10000),
      Text("screenshot", "FILE", "write the window as this PNG file, then exit"),
      Number("after", "S", "seconds after start to take the screenshot (default 2)").Range(0, 1e6),
      Number("frames", "N", "take the screenshot after this many frames instead").Range(1, 1e9),
      Number("quit-after", "S", "exit after this many seconds and print frame figures")
          .Range(0, 1e9),
      Text("camera", "X,Y,Z,YAW,PITCH,DISTANCE",
           "fixed start camera: target [m], yaw and pitch [deg], distance [m]; turns follow off"),
      Text("show", "NAMES", std::string("turn these on at start (comma-separated): ") + kToggleNames),
      Text("hide", "NAMES", "turn these off at start (same names)"),
      Number("nice", "N",
             "lower the viewer's CPU priority by this much, 0 to 19 (default 5): on a machine "
             "without a GPU drawing takes about a core, and the sim keeping real time matters more")
          .Range(0, 19),
      Text("camera-image", "NAME",
           "show the colour image of camera sensor NAME (published by simpartner-camera on "
           "SIM_IMAGE) in the bottom-right corner; key i shows the next camera's"),
      Number("scanner-poll", "HZ",
             "ask every scanner for a reading this many times per second (default 0: only draw "
             "readings the sim publishes at the sensor's rate)")
          .Range(0, 1000),
  };
  spec.parameters = ParameterUse{{parameter_sections::kTransport}};
  return spec;
}

ViewerOptions MakeViewerOptions(const CommandLine& command_line, const Parameters& params) {
  DiagnosticList diagnostics;
  ViewerOptions o;
  // With the large receive buffer (bus_url.h): a viewer busy drawing a
  // frame misses no state of a sim running faster than real time.
  o.lcm_url = WithReceiveBuffer(params.lcmUrl);
  o.width = static_cast<int>(command_line.Number("width", o.width));
  o.height = static_cast<int>(command_line.Number("height", o.height));
  o.max_fps = command_line.Number("fps", o.max_fps);
  o.after_seconds = command_line.Number("after", o.after_seconds);
  o.after_frames = static_cast<int64_t>(command_line.Number("frames", 0));
  o.quit_after = command_line.Number("quit-after", o.quit_after);
  o.scanner_poll_hz = command_line.Number("scanner-poll", o.scanner_poll_hz);
  o.nice = static_cast<int>(command_line.Number("nice", o.nice));
  o.screenshot = command_line.Text("screenshot");
  o.camera_image = command_line.Text("camera-image");
  const bool timed = o.after_seconds > 0 || o.after_frames > 0;
  if (o.screenshot.empty() && timed)
    diagnostics.Add(kCommandLine, 0, o.after_frames > 0 ? "--frames" : "--after",
                    "only applies with --screenshot FILE");
  if (!o.screenshot.empty() && !timed) o.after_seconds = 2.0;

  const std::string camera = command_line.Text("camera");
  if (!camera.empty()) {
    const std::vector<std::string> parts = Split(camera, ',');
    if (parts.size() != 6) {
      diagnostics.Add(kCommandLine, 0, "--camera",
                      "value '" + camera + "' is not 6 numbers 'x,y,z,yaw,pitch,distance'");
    } else {
      CameraSpec spec;
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const auto v = NumberInRange("camera", parts[static_cast<size_t>(k)], -1e6, 1e6, &diagnostics);
        ok &= v.has_value();
        if (v) spec.target[k] = *v;
      }
      const auto yaw = NumberInRange("camera", parts[3], -360, 360, &diagnostics);
      const auto pitch = NumberInRange("camera", parts[4], -89, 89, &diagnostics);
      const auto distance = NumberInRange("camera", parts[5], 0.05, 1000, &diagnostics);
      if (ok && yaw && pitch && distance) {
        spec.yaw_deg = *yaw;
        spec.pitch_deg = *pitch;
        spec.distance = *distance;
        o.camera = spec;
        o.toggles.follow = false;
      }
    }
  }
  for (const char* flag : {"show", "hide"}) {
    const std::string list = command_line.Text(flag);
    if (list.empty()) continue;
    for (const std::string& name : Split(list, ',')) {
      bool* toggle = ToggleByName(&o.toggles, name);
      if (toggle == nullptr) {
        diagnostics.Add(kCommandLine, 0, std::string("--") + flag,
                        "'" + name + "' is not one of " + kToggleNames);
        continue;
      }
      *toggle = std::string(flag) == "show";
    }
  }
  if (!diagnostics.empty()) throw ConfigError(diagnostics);
  return o;
}

Camera CameraFromSpec(const CameraSpec& spec, const Eigen::Vector3d& up) {
  Camera camera;
  camera.up = up.normalized();
  camera.target = Eigen::Vector3d(spec.target[0], spec.target[1], spec.target[2]);
  camera.yaw = spec.yaw_deg * M_PI / 180;
  camera.pitch = spec.pitch_deg * M_PI / 180;
  camera.distance = spec.distance;
  return camera;
}

}  // namespace simpartner::viewer
