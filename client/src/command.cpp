#include "simpartner/client/command.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "simpartner/actuator_t.hpp"
#include "simpartner/client/errors.h"
#include "simpartner/command_shape.h"
#include "simpartner/text.h"
#include "simpartner/text.h"

namespace simpartner::client {
namespace {

command_t Addressed(const Target& target, int action, int64_t apply_at_step) {
  command_t command{};
  command.utime = 0;
  command.request_id = 0;
  command.robot = target.robot;
  command.target = target.name;
  command.port = 0;
  command.action = static_cast<int8_t>(action);
  command.apply_at_step = apply_at_step;
  command.num_values = 0;
  return command;
}

void CheckSize(const Target& target, const command_t& command) {
  const size_t bytes = EncodedSize(command);
  if (bytes > kMaxCommandBytes)
    throw BadValues(target.name, "values",
                    std::to_string(command.values.size()) + " values, " +
                        std::to_string(command.text.size()) + " text bytes",
                    "the command encodes to " + std::to_string(bytes) + " bytes; at most " +
                        std::to_string(kMaxCommandBytes) + " are sent on the bus");
}

std::string JoinValues(const std::vector<double>& values) {
  std::string out;
  for (size_t k = 0; k < values.size(); ++k) out += (k ? "," : "") + FormatNumber(values[k], 17);
  return out;
}

}  // namespace

size_t EncodedSize(const command_t& command) {
  return static_cast<size_t>(command.getEncodedSize());
}

std::vector<double> ParseValueText(const std::string& target_name, const std::string& text) {
  std::vector<double> values;
  if (Trim(text).empty()) return values;
  std::string item;
  std::istringstream in(text);
  size_t index = 0;
  while (std::getline(in, item, ',')) {
    const std::string trimmed = Trim(item);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(trimmed.c_str(), &end);
    if (trimmed.empty() || *end != '\0')
      throw BadValues(target_name, "values[" + std::to_string(index) + "]", trimmed,
                      "expected a number (values are comma-separated, e.g. 1000,0.5)");
    if (!std::isfinite(v))
      throw BadValues(target_name, "values[" + std::to_string(index) + "]", trimmed,
                      "expected a finite number");
    values.push_back(v);
    ++index;
  }
  // "1,2," leaves an empty last item that getline does not return.
  if (!text.empty() && Trim(text).back() == ',')
    throw BadValues(target_name, "values[" + std::to_string(index) + "]", "",
                    "expected a number after the last comma");
  return values;
}

command_t BuildCommand(const Target& target, int action, const std::vector<double>& values,
                       int64_t apply_at_step) {
  const CommandTargetShape shape = target.shape();
  if (apply_at_step < -1)
    throw BadValues(target.name, "apply_at_step", std::to_string(apply_at_step),
                    "expected a step >= 0, or -1 for 'as soon as received'");
  const std::string count_error =
      CheckValueCount(shape, action, static_cast<int>(values.size()));
  if (!count_error.empty())
    throw BadValues(target.name, std::string(ActionName(action)) + " values",
                    JoinValues(values),
                    target.kind_name() + " '" + target.name + "': " + count_error);
  const std::vector<std::string> names =
      ValueNames(shape, action, static_cast<int>(values.size()));
  for (size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k]))
      throw BadValues(target.name,
                      "values[" + std::to_string(k) + "]" +
                          (k < names.size() ? " (" + names[k] + ")" : std::string()),
                      FormatNumber(values[k], 17), "expected a finite number");
  }
  command_t command = Addressed(target, action, apply_at_step);
  command.values = values;
  command.num_values = static_cast<int32_t>(values.size());
  CheckSize(target, command);
  return command;
}

command_t BuildCommandFromText(const Target& target, int action, const std::string& text,
                               int64_t apply_at_step) {
  const std::vector<int> counts = AcceptedValueCounts(target.shape(), action);
  const bool echo_text = counts.size() == 1 && counts.front() < 0;
  if (!echo_text) {
    command_t command = BuildCommand(target, action, ParseValueText(target.name, text),
                                     apply_at_step);
    // The original's text goes along, so the reply and the log show it.
    command.text = Trim(text);
    CheckSize(target, command);
    return command;
  }
  if (apply_at_step < -1)
    throw BadValues(target.name, "apply_at_step", std::to_string(apply_at_step),
                    "expected a step >= 0, or -1 for 'as soon as received'");
  command_t command = Addressed(target, action, apply_at_step);
  command.text = text;
  CheckSize(target, command);
  return command;
}

command_t SetVelocity(const Target& target, const std::vector<double>& velocity,
                      double max_force, int64_t apply_at_step) {
  std::vector<double> values(velocity.size(), max_force);
  values.insert(values.end(), velocity.begin(), velocity.end());
  return BuildCommand(target, command_t::ACTION_SET, values, apply_at_step);
}

command_t SetAngle(const Target& target, const std::vector<double>& angle, double p, double i,
                   double d, double max_force, int64_t apply_at_step) {
  std::vector<double> values(angle.size(), max_force);
  values.insert(values.end(), angle.begin(), angle.end());
  values.insert(values.end(), {p, i, d});
  return BuildCommand(target, command_t::ACTION_SET, values, apply_at_step);
}

command_t Hold(const Target& target, double max_force, int64_t apply_at_step) {
  return BuildCommand(target, command_t::ACTION_HOLD,
                      std::vector<double>(static_cast<size_t>(target.num_axes), max_force),
                      apply_at_step);
}

command_t Read(const Target& target, int64_t apply_at_step) {
  return BuildCommand(target, command_t::ACTION_READ, {}, apply_at_step);
}

std::vector<command_t> StopWheelsCommands(const Catalog& catalog, double max_force) {
  std::vector<command_t> commands;
  for (const Target& t : catalog.targets()) {
    if (!t.is_actuator() || t.lcm_kind != actuator_t::KIND_JOINT_VELOCITY) continue;
    commands.push_back(
        SetVelocity(t, std::vector<double>(static_cast<size_t>(t.num_axes), 0.0), max_force));
  }
  return commands;
}

}  // namespace simpartner::client
