#include "message_rules.h"
#include "simpartner/message_checks.h"

namespace simpartner {
namespace {

using message_rules::MessageRules;

// The reading is of a sensor of the model, of that sensor's kind and name.
MessageCheck CheckFitsModel(const sensor_reading_t& r, const ModelOutline& model,
                            const MessageRules& rules) {
  const int64_t sensors = static_cast<int64_t>(model.sensors.size());
  if (r.sensor < 0 || r.sensor >= sensors)
    return rules.Problem(MessageFault::kBadIndex, "sensor",
                         " = " + std::to_string(r.sensor) + " but the model of simulation " +
                             std::to_string(model.simulation_id) + " has " +
                             std::to_string(sensors) + " sensors");
  const ModelOutline::Sensor& sensor = model.sensors[static_cast<size_t>(r.sensor)];
  if (r.kind != sensor.kind)
    return rules.Problem(MessageFault::kNotTheModels, "kind",
                         " = " + std::to_string(r.kind) + " but sensor " +
                             std::to_string(r.sensor) + " ('" + sensor.name +
                             "') of the model is of kind " + std::to_string(sensor.kind));
  if (r.name != sensor.name)
    return rules.Problem(MessageFault::kNotTheModels, "name",
                         " = '" + r.name + "' but sensor " + std::to_string(r.sensor) +
                             " of the model is '" + sensor.name + "'");
  return std::nullopt;
}

}  // namespace

MessageCheck CheckSensorReading(const sensor_reading_t& reading, const ModelOutline* model) {
  const MessageRules rules("sensor_reading_t");
  if (model)
    if (auto bad = CheckFitsModel(reading, *model, rules)) return bad;
  if (auto bad = rules.Finite("sim_time", reading.sim_time)) return bad;
  if (auto bad = rules.Finite("values", reading.values.data(), reading.values.size())) return bad;
  return rules.Text("text", reading.text, message_rules::kTextBytes);
}

}  // namespace simpartner
