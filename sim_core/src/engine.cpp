#include "simpartner/sim/engine.h"

#include <cmath>

#include "mujoco_world.h"
#include "ode_world.h"
#include "simpartner/text.h"

namespace simpartner::sim {
namespace {

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

EngineError::EngineError(const std::string& engine, std::string engine_message, std::string during,
                         std::vector<std::string> bodies)
    : Error(engine + " failed: " + engine_message +
            (during.empty() ? "" : " (during " + during + ")") + "; bodies: " +
            (bodies.empty() ? std::string("none stands out") : Join(bodies))),
      engine_message_(std::move(engine_message)),
      during_(std::move(during)),
      bodies_(std::move(bodies)) {}

void SetStopsOfTheFiles(const model::FlatModel& model, PhysicsEngine* engine) {
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const model::FlatJoint& flat = model.joints[j];
    for (int axis = 0; axis < flat.num_axes; ++axis) {
      const double lo = flat.source->lo_stop[axis], hi = flat.source->hi_stop[axis];
      if (std::isfinite(lo) || std::isfinite(hi))
        engine->SetStops(static_cast<int>(j), axis, lo, hi);
    }
  }
}

std::unique_ptr<PhysicsEngine> MakeEngine(const model::FlatModel& model,
                                          const Parameters& params) {
  if (params.engine == "mujoco") return std::make_unique<MujocoWorld>(model, params);
  return std::make_unique<OdeWorld>(model, params);
}

std::vector<Diagnostic> EngineLimits(const model::FlatModel& model, const Parameters& params) {
  if (params.engine == "mujoco") return MujocoLimits(model, params);
  return {};
}

std::vector<std::string> ParametersTheEngineIgnores(const Parameters& params) {
  if (params.engine != "mujoco") return {};
  const Parameters defaults;
  std::vector<std::string> out;
  auto note = [&](const char* key, bool differs, const std::string& value) {
    if (differs) out.push_back(std::string(key) + "=" + value);
  };
  note("stepper", params.stepper != defaults.stepper, params.stepper);
  note("quickStepIterations", params.quickStepIterations != defaults.quickStepIterations,
       std::to_string(params.quickStepIterations));
  note("quickStepW", params.quickStepW != defaults.quickStepW, ShortestNumber(params.quickStepW));
  note("autoDisableFlag", params.autoDisableFlag != defaults.autoDisableFlag,
       params.autoDisableFlag ? "1" : "0");
  note("maxContacts", params.maxContacts != defaults.maxContacts,
       std::to_string(params.maxContacts));
  return out;
}

}  // namespace simpartner::sim
