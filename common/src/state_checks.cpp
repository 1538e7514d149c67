#include <tuple>
#include <utility>

#include "message_rules.h"
#include "simpartner/message_checks.h"
#include "simpartner/text.h"

namespace simpartner {
namespace {

using message_rules::MessageRules;

MessageCheck CheckCounts(const state_t& s, const ModelOutline& model, const MessageRules& rules) {
  for (const auto& [field, count, expected] :
       {std::tuple<const char*, int32_t, int32_t>{"num_bodies", s.num_bodies, model.bodies},
        {"num_joints", s.num_joints, model.joints}})
    if (count != expected)
      return rules.Problem(MessageFault::kCountMismatch, field,
                           " = " + std::to_string(count) + " but the model of simulation " +
                               std::to_string(model.simulation_id) + " has " +
                               std::to_string(expected));
  return std::nullopt;
}

MessageCheck CheckBodies(const state_t& s, const MessageRules& rules) {
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    const body_state_t& b = s.bodies[i];
    const MessageRules at = rules.In("bodies", i);
    if (auto bad = at.Finite("position", b.position, 3)) return bad;
    if (auto bad = at.Finite("contact_force", b.contact_force, 3)) return bad;
    if (auto bad = at.Finite("contact_torque", b.contact_torque, 3)) return bad;
    if (auto bad = at.UnitQuaternion("orientation", b.orientation)) return bad;
  }
  return std::nullopt;
}

MessageCheck CheckJoints(const state_t& s, const MessageRules& rules) {
  for (size_t j = 0; j < s.joints.size(); ++j) {
    const joint_state_t& js = s.joints[j];
    const MessageRules at = rules.In("joints", j);
    for (const auto& [field, values] :
         {std::pair<const char*, const double*>{"position", js.position}, {"rate", js.rate},
          {"anchor", js.anchor}, {"force1", js.force1}, {"torque1", js.torque1}})
      if (auto bad = at.Finite(field, values, 3)) return bad;
  }
  return std::nullopt;
}

// Each wheel on soil has finite figures and, with the model, is a body of it.
MessageCheck CheckWheelSoil(const state_t& s, const ModelOutline* model,
                            const MessageRules& rules) {
  for (size_t w = 0; w < s.wheel_soil.size(); ++w) {
    const wheel_soil_t& ws = s.wheel_soil[w];
    const MessageRules at = rules.In("wheel_soil", w);
    if (model && (ws.body < 0 || ws.body >= model->bodies))
      return at.Problem(MessageFault::kBadIndex, "body",
                        " = " + std::to_string(ws.body) + " but the model of simulation " +
                            std::to_string(model->simulation_id) + " has " +
                            std::to_string(model->bodies) + " bodies");
    for (const auto& [field, value] :
         {std::pair<const char*, double>{"sinkage", ws.sinkage}, {"slip", ws.slip},
          {"thrust", ws.thrust}, {"drawbar_pull", ws.drawbar_pull}, {"load", ws.load},
          {"axle_torque", ws.axle_torque}})
      if (auto bad = at.Finite(field, value)) return bad;
    if (auto bad = at.Finite("normal_force", ws.normal_force, 3)) return bad;
    if (auto bad = at.Finite("shear_force", ws.shear_force, 3)) return bad;
  }
  return std::nullopt;
}

}  // namespace

MessageCheck CheckState(const state_t& state, const ModelOutline* model) {
  const MessageRules rules("state_t");
  if (model)
    if (auto bad = CheckCounts(state, *model, rules)) return bad;
  if (state.step < 0)
    return rules.Problem(MessageFault::kOutOfRange, "step",
                         " = " + std::to_string(state.step) + " (negative)");
  if (auto bad = rules.Finite("sim_time", state.sim_time)) return bad;
  if (auto bad = CheckBodies(state, rules)) return bad;
  if (auto bad = CheckJoints(state, rules)) return bad;
  return CheckWheelSoil(state, model, rules);
}

}  // namespace simpartner
