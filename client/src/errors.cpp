#include "simpartner/client/errors.h"

#include <cstdio>

namespace simpartner::client {
namespace {

std::string SecondsText(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", seconds);
  return text;
}

std::string UnknownMessage(const std::string& name, const std::vector<std::string>& suggestions,
                           const std::string& detail) {
  std::string message = detail.empty() ? "'" + name + "' is not an actuator or sensor of the model"
                                       : detail;
  if (!suggestions.empty()) {
    message += "; did you mean ";
    for (size_t k = 0; k < suggestions.size(); ++k) {
      if (k) message += k + 1 == suggestions.size() ? " or " : ", ";
      message += "'" + suggestions[k] + "'";
    }
    message += "?";
  }
  return message;
}

}  // namespace

UnknownTarget::UnknownTarget(std::string name, std::vector<std::string> suggestions,
                             std::string detail)
    : ClientError(UnknownMessage(name, suggestions, detail)),
      name_(std::move(name)),
      suggestions_(std::move(suggestions)) {}

Refused::Refused(std::string target, std::string reason, int64_t request_id)
    : ClientError(target + ": refused by the sim: " + reason),
      target_(std::move(target)),
      reason_(std::move(reason)),
      request_id_(request_id) {}

Timeout::Timeout(std::string awaited, double seconds, std::string url, std::string hint)
    : ClientError("no " + awaited + " within " + SecondsText(seconds) + " on " + url +
                  (hint.empty() ? "" : "; " + hint)),
      awaited_(std::move(awaited)),
      seconds_(seconds) {}

NoSim::NoSim(std::string url, double seconds, std::string hint)
    : ClientError(seconds > 0 ? "no sim on " + url + ": no SIM_MODEL within " + SecondsText(seconds) +
                                    (hint.empty() ? " (is simpartner-sim running with this --lcm-url?)"
                                                  : "; " + hint)
                              : "no model learned from " + url +
                                    " yet (the client was made with learn_model = false: "
                                    "call Relearn())"),
      url_(std::move(url)),
      seconds_(seconds) {}

SimRestarted::SimRestarted(int64_t old_simulation_id, int64_t new_simulation_id)
    : ClientError("the sim restarted: simulation id " + std::to_string(old_simulation_id) +
                  " became " + std::to_string(new_simulation_id) +
                  " (its model and settings start over)"),
      old_id_(old_simulation_id),
      new_id_(new_simulation_id) {}

BadValues::BadValues(std::string target, std::string field, std::string value,
                     std::string expected)
    : ClientError(target + ": " + field + " = '" + value + "': " + expected),
      target_(std::move(target)),
      field_(std::move(field)),
      value_(std::move(value)),
      expected_(std::move(expected)) {}

LockStepError::LockStepError(std::string controller, std::string what, int64_t tick)
    : ClientError("lock-step controller '" + controller + "': " + what),
      controller_(std::move(controller)),
      tick_(tick) {}

SimStopped::SimStopped(int64_t step)
    : ClientError("the sim stopped at step " + std::to_string(step) +
                  " (its duration reached, or told to quit)"),
      step_(step) {}

}  // namespace simpartner::client
