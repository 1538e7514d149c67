#include "simpartner/viewer/hud_text.h"

#include <iomanip>
#include <sstream>

#include "simpartner/sim_engine.h"

namespace simpartner::viewer {
namespace {

const char* RunStateName(int8_t run_state) {
  switch (run_state) {
    case status_t::RUN_RUNNING: return "RUNNING";
    case status_t::RUN_PAUSED: return "PAUSED";
    case status_t::RUN_STOPPED: return "STOPPED";
    case status_t::RUN_FAULTED: return "FAULTED";
    case status_t::RUN_RESET: return "RESET";
  }
  return "?";
}

}  // namespace

std::string Fixed(double v, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

std::string SimLine(const model_t& model, const state_t* state, const status_t* status) {
  std::string line = model.world_name;
  if (!model.robots.empty()) line += " / " + model.robots[0].model;
  line += "   engine " + SimEngine(model.engine);
  if (state != nullptr) {
    line += "   t " + Fixed(state->sim_time, 3) + " s   step " + std::to_string(state->step);
  } else if (status != nullptr) {
    line += "   t " + Fixed(status->sim_time, 3) + " s   step " + std::to_string(status->step);
  } else {
    line += "   no state yet";
  }
  if (status != nullptr)
    line += "   x" + Fixed(status->real_time_factor, 2) + " real time   " +
            RunStateName(status->run_state);
  return line;
}

}  // namespace simpartner::viewer
