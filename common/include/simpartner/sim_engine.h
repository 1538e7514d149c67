// The physics engine a simulation runs on, as SIM_MODEL and SIM_STATUS
// name it (model_t.engine, status_t.engine: "ode" or "mujoco").
#pragma once

#include <string>

namespace simpartner {

// The engine a message names. An empty field comes from a sender that does
// not fill it (written before the field existed); every such sim ran ODE,
// the only engine there was, so it reads "ode".
inline std::string SimEngine(const std::string& engine_field) {
  return engine_field.empty() ? "ode" : engine_field;
}

}  // namespace simpartner
