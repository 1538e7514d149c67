#include "simpartner/teleop/frontends.h"

#include <SDL2/SDL.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <cstdio>
#include <deque>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "simpartner/client/errors.h"
#include "simpartner/teleop/keyboard_window.h"
#include "simpartner/teleop/session.h"
#include "simpartner/teleop/teleop_cli.h"

namespace simpartner::teleop {

// ---- Gamepad ----

Gamepad::~Gamepad() {
  if (controller_) SDL_GameControllerClose(controller_);
}

void Gamepad::OpenFirst() {
  if (controller_) return;
  for (int i = 0; i < SDL_NumJoysticks(); ++i) {
    if (!SDL_IsGameController(i)) continue;
    controller_ = SDL_GameControllerOpen(i);
    if (!controller_) {
      log_ << "teleop: cannot open game controller " << i << ": " << SDL_GetError() << std::endl;
      continue;
    }
    instance_id_ = SDL_JoystickInstanceID(SDL_GameControllerGetJoystick(controller_));
    log_ << "teleop: controller connected: " << name() << std::endl;
    return;
  }
}

void Gamepad::Handle(const SDL_Event& event) {
  if (event.type == SDL_CONTROLLERDEVICEADDED) {
    OpenFirst();
  } else if (event.type == SDL_CONTROLLERDEVICEREMOVED && controller_ &&
             event.cdevice.which == instance_id_) {
    log_ << "teleop: controller unplugged: " << name() << std::endl;
    SDL_GameControllerClose(controller_);
    controller_ = nullptr;
    instance_id_ = -1;
    OpenFirst();  // another one, if there is
  }
}

InputState Gamepad::Read() const {
  InputState in;
  if (!controller_ || !SDL_GameControllerGetAttached(controller_)) return in;
  in.connected = true;
  for (int a = 0; a < kAxisCount; ++a)
    in.axis[a] = AxisFromSdl(
        SDL_GameControllerGetAxis(controller_, static_cast<SDL_GameControllerAxis>(a)));
  for (int b = 0; b < kButtonCount; ++b)
    in.button[b] =
        SDL_GameControllerGetButton(controller_, static_cast<SDL_GameControllerButton>(b)) != 0;
  return in;
}

std::string Gamepad::name() const {
  const char* n = controller_ ? SDL_GameControllerName(controller_) : nullptr;
  return n ? n : (controller_ ? "(unnamed controller)" : "");
}

std::vector<std::string> ListControllers() {
  std::vector<std::string> names;
  for (int i = 0; i < SDL_NumJoysticks(); ++i) {
    if (!SDL_IsGameController(i)) continue;
    const char* n = SDL_GameControllerNameForIndex(i);
    names.push_back(std::to_string(i) + ": " + (n ? n : "(unnamed controller)"));
  }
  return names;
}

// ---- Keyboard ----

InputState KeyboardInput(const Plan* plan) {
  InputState in;
  in.connected = true;
  const Uint8* keys = SDL_GetKeyboardState(nullptr);
  auto held = [&](SDL_Scancode a, SDL_Scancode b = SDL_SCANCODE_UNKNOWN) {
    return keys[a] || (b != SDL_SCANCODE_UNKNOWN && keys[b]);
  };
  const double forward = held(SDL_SCANCODE_UP, SDL_SCANCODE_W) ? 1.0 : 0.0;
  const double back = held(SDL_SCANCODE_DOWN, SDL_SCANCODE_S) ? 1.0 : 0.0;
  const double left = held(SDL_SCANCODE_LEFT, SDL_SCANCODE_A) ? 1.0 : 0.0;
  const double right = held(SDL_SCANCODE_RIGHT, SDL_SCANCODE_D) ? 1.0 : 0.0;
  // A stick pushed up reads negative on SDL's y axes.
  in.axis[SDL_CONTROLLER_AXIS_LEFTY] = back - forward;
  in.axis[SDL_CONTROLLER_AXIS_LEFTX] = right - left;
  if (!plan) return in;
  // The mapping's own axes and buttons, so the keyboard follows any file.
  if (plan->drive_axis >= 0 && plan->drive_axis != SDL_CONTROLLER_AXIS_LEFTY)
    in.axis[plan->drive_axis] = back - forward;
  if (plan->steer && plan->steer->axis >= 0 && plan->steer->axis != SDL_CONTROLLER_AXIS_LEFTX)
    in.axis[plan->steer->axis] = right - left;
  if (plan->deadman_button >= 0) in.button[plan->deadman_button] = held(SDL_SCANCODE_SPACE);
  const SDL_Scancode level_keys[3][2] = {{SDL_SCANCODE_R, SDL_SCANCODE_F},
                                         {SDL_SCANCODE_Q, SDL_SCANCODE_E},
                                         {SDL_SCANCODE_O, SDL_SCANCODE_C}};
  for (size_t k = 0; k < plan->levels.size() && k < 3; ++k) {
    const Plan::Level& level = plan->levels[k];
    if (level.button_plus >= 0) in.button[level.button_plus] |= held(level_keys[k][0]);
    if (level.button_minus >= 0) in.button[level.button_minus] |= held(level_keys[k][1]);
  }
  return in;
}

// ---- Virtual pad ----

VirtualPad::~VirtualPad() { Detach(); }

void VirtualPad::Attach() {
  if (joystick_) return;
  SDL_VirtualJoystickDesc desc;
  SDL_zero(desc);
  desc.version = SDL_VIRTUAL_JOYSTICK_DESC_VERSION;
  desc.type = SDL_JOYSTICK_TYPE_GAMECONTROLLER;
  desc.naxes = SDL_CONTROLLER_AXIS_MAX;
  desc.nbuttons = SDL_CONTROLLER_BUTTON_MAX;
  desc.axis_mask = (1u << SDL_CONTROLLER_AXIS_MAX) - 1;
  desc.button_mask = (1u << SDL_CONTROLLER_BUTTON_MAX) - 1;
  desc.name = "SimPartner virtual pad";
  device_index_ = SDL_JoystickAttachVirtualEx(&desc);
  if (device_index_ < 0)
    throw std::runtime_error(std::string("cannot attach a virtual joystick: ") + SDL_GetError());
  joystick_ = SDL_JoystickOpen(device_index_);
  if (!joystick_)
    throw std::runtime_error(std::string("cannot open the virtual joystick: ") + SDL_GetError());
  log_ << "vpad: attached" << std::endl;
}

void VirtualPad::Detach() {
  if (!joystick_) return;
  const SDL_JoystickID id = SDL_JoystickInstanceID(joystick_);
  SDL_JoystickClose(joystick_);
  joystick_ = nullptr;
  for (int i = 0; i < SDL_NumJoysticks(); ++i)
    if (SDL_JoystickIsVirtual(i) && SDL_JoystickGetDeviceInstanceID(i) == id) {
      SDL_JoystickDetachVirtual(i);
      break;
    }
  log_ << "vpad: detached" << std::endl;
}

bool VirtualPad::Apply(const std::string& line) {
  std::istringstream in(line);
  std::string verb, name, value;
  in >> verb >> name >> value;
  if (verb.empty() || verb[0] == '#') return true;
  auto bad = [&](const std::string& why) {
    return std::runtime_error("vpad script line '" + line + "': " + why);
  };
  if (verb == "quit") return false;
  if (verb == "attach") {
    Attach();
    return true;
  }
  if (verb == "detach") {
    Detach();
    return true;
  }
  if (!joystick_) throw bad("the pad is detached");
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v)) throw bad("'" + value + "' is not a number");
  if (verb == "axis") {
    const SDL_GameControllerAxis axis = SDL_GameControllerGetAxisFromString(name.c_str());
    if (axis == SDL_CONTROLLER_AXIS_INVALID) throw bad("unknown axis '" + name + "'");
    if (v < -1 || v > 1) throw bad("axis value " + value + " is outside -1..1");
    SDL_JoystickSetVirtualAxis(joystick_, axis, static_cast<Sint16>(std::lround(v * 32767)));
  } else if (verb == "button") {
    const SDL_GameControllerButton button = SDL_GameControllerGetButtonFromString(name.c_str());
    if (button == SDL_CONTROLLER_BUTTON_INVALID) throw bad("unknown button '" + name + "'");
    SDL_JoystickSetVirtualButton(joystick_, button, v != 0 ? 1 : 0);
  } else {
    throw bad("unknown command '" + verb + "' (axis, button, attach, detach, quit)");
  }
  return true;
}

// ---- The program ----

namespace {

// Reads what stdin has (non-blocking), returns the complete lines.
std::vector<std::string> ReadAvailableLines(int input_fd, std::string* pending, bool* eof) {
  std::vector<std::string> lines;
  pollfd fd{input_fd, POLLIN, 0};
  while (!*eof && ::poll(&fd, 1, 0) > 0) {
    char buffer[4096];
    const ssize_t n = ::read(input_fd, buffer, sizeof buffer);
    if (n <= 0) {
      *eof = true;
      break;
    }
    pending->append(buffer, static_cast<size_t>(n));
  }
  for (size_t nl; (nl = pending->find('\n')) != std::string::npos;) {
    lines.push_back(pending->substr(0, nl));
    pending->erase(0, nl + 1);
  }
  return lines;
}

// What a script line sets: "button a", "axis leftx", "attach", ...
std::string ControlOf(const std::string& line) {
  std::istringstream in(line);
  std::string verb, name;
  in >> verb >> name;
  return verb + " " + name;
}

// Applies the script's waiting lines in order (false once one says quit).
// It stops before a line that sets a control already set in this pass: the
// controller reads the pad once a pass, so a press and its release read
// together (the loop late on a loaded machine) would be a press never seen.
// Such a line waits for the next pass.
bool ApplyScriptLines(VirtualPad& pad, std::deque<std::string>* lines, std::ostream& err) {
  std::set<std::string> set_now;
  while (!lines->empty()) {
    const std::string& line = lines->front();
    if (!set_now.insert(ControlOf(line)).second) break;
    try {
      if (!pad.Apply(line)) return false;
    } catch (const std::exception& e) {
      err << "simpartner-teleop-vpad: " << e.what() << std::endl;
    }
    lines->pop_front();
  }
  return true;
}

}  // namespace

int RunTeleop(const std::vector<std::string>& args, bool virtual_pad, std::ostream& out,
              std::ostream& err) {
  const CommandLineSpec spec = TeleopCommandLine(virtual_pad);
  CommandLine command_line;
  if (const auto done = ReadCommandLine(spec, args, out, err, &command_line)) return *done;
  const TeleopOptions options = MakeTeleopOptions(command_line, virtual_pad);
  if (options.check) {
    if (options.environment.empty())
      return ReportUsageError(spec, "--check needs --environment WORLD", err);
    return CheckMapping(options, out, err);
  }
  const bool keyboard = options.input == TeleopInput::kKeyboard;

  // SIGINT and SIGTERM are taken synchronously (sigtimedwait in the loop):
  // blocked here, before any thread starts, so every thread inherits it.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
  SDL_SetHint(SDL_HINT_JOYSTICK_ALLOW_BACKGROUND_EVENTS, "1");
  const Uint32 subsystems =
      keyboard ? SDL_INIT_VIDEO | SDL_INIT_EVENTS : SDL_INIT_GAMECONTROLLER | SDL_INIT_EVENTS;
  if (SDL_Init(subsystems) != 0) {
    err << "simpartner-teleop: SDL cannot start: " << SDL_GetError() << "\n";
    return 1;
  }
  struct SdlQuit {
    ~SdlQuit() { SDL_Quit(); }
  } sdl_quit;

  if (options.list) {
    const std::vector<std::string> names = ListControllers();
    if (names.empty()) out << "no game controller connected\n";
    for (const std::string& n : names) out << n << "\n";
    return 0;
  }

  std::unique_ptr<Session> session;
  try {
    session = std::make_unique<Session>(options.session, out);
  } catch (const client::ClientError& e) {
    err << "simpartner-teleop: " << e.what() << "\n";
    return 1;
  }

  Gamepad gamepad(out);
  VirtualPad pad(out);
  std::unique_ptr<KeyboardWindow> window;
  if (keyboard) {
    try {
      window = std::make_unique<KeyboardWindow>();
    } catch (const std::runtime_error& e) {
      err << "simpartner-teleop: " << e.what() << "\n";
      return 1;
    }
    out << "teleop: keyboard window open (hold space and use the arrows or WASD)" << std::endl;
  } else {
    if (virtual_pad) {
      try {
        pad.Attach();
      } catch (const std::exception& e) {
        err << "simpartner-teleop-vpad: " << e.what() << "\n";
        return 1;
      }
    }
    gamepad.OpenFirst();
    if (gamepad.name().empty())
      out << "teleop: no game controller yet; plug one in (or use --input keyboard)" << std::endl;
  }

  // The test build's script: a file or FIFO (--script), else stdin.
  int script_fd = STDIN_FILENO;
  if (virtual_pad && !options.script.empty()) {
    script_fd = ::open(options.script.c_str(), O_RDONLY | O_CLOEXEC);
    if (script_fd < 0) {
      err << "simpartner-teleop-vpad: cannot open script " << options.script << ": " << std::strerror(errno)
          << "\n";
      return 1;
    }
  }
  std::string pending;
  std::deque<std::string> script_lines;
  bool eof = false;
  int exit_status = 0;
  auto last_status = std::chrono::steady_clock::now();
  std::string last_line;
  InputState input;
  for (bool running = true; running;) {
    SDL_Event event;
    while (SDL_PollEvent(&event)) {
      if (event.type == SDL_QUIT) running = false;
      if (keyboard && event.type == SDL_KEYDOWN && event.key.keysym.sym == SDLK_ESCAPE)
        running = false;
      if (!keyboard) gamepad.Handle(event);
    }
    if (virtual_pad) {
      for (std::string& line : ReadAvailableLines(script_fd, &pending, &eof))
        script_lines.push_back(std::move(line));
      if (!ApplyScriptLines(pad, &script_lines, err)) running = false;
      if (eof && script_lines.empty()) running = false;
      // The virtual pad's values reach the controller in the next pump.
      SDL_PumpEvents();
      while (SDL_PollEvent(&event)) gamepad.Handle(event);
    }
    const Plan* plan = session->controller() ? &session->controller()->plan() : nullptr;
    input = keyboard ? KeyboardInput(plan) : gamepad.Read();
    timespec no_wait{0, 0};
    const int signal = sigtimedwait(&stop_signals, nullptr, &no_wait);
    if (signal > 0) {
      out << "teleop: " << (signal == SIGINT ? "SIGINT" : "SIGTERM")
          << ": stopping the wheels and holding the joints" << std::endl;
      break;
    }
    session->Tick(input);

    const auto now = std::chrono::steady_clock::now();
    if (now - last_status > std::chrono::milliseconds(500)) {
      last_status = now;
      const std::string line = session->StatusLine();
      if (line != last_line) out << "teleop: " << line << std::endl;
      last_line = line;
    }
    if (window) window->Update(session->StatusLine(), session->demand().stop, KeyboardHelpLines(plan));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  session->StopAndFlush(input);
  out << "teleop: stopped (" << session->batches_sent() << " command batches sent)" << std::endl;
  if (script_fd != STDIN_FILENO) ::close(script_fd);
  return exit_status;
}

}  // namespace simpartner::teleop
