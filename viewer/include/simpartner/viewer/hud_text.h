// The text of the viewer's HUD, apart from the window so that it is
// tested without a display.
#pragma once

#include <string>

#include "simpartner/model_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner::viewer {

// `v` with `decimals` digits after the point: Fixed(1.2345, 2) = "1.23".
std::string Fixed(double v, int decimals);

// The HUD's first line: world / robot, the physics engine, time and step
// (of the newest state, else of the status), speed and run state (of the
// status, when one has come).
std::string SimLine(const model_t& model, const state_t* state, const status_t* status);

}  // namespace simpartner::viewer
