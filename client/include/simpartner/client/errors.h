// Typed errors of the client library. Each carries the context a message
// needs (what was addressed, what the sim said, how long was waited), and
// what() is a complete sentence a program can print as it is.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace simpartner::client {

class ClientError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A name or port the model does not have. suggestions: nearest names.
class UnknownTarget : public ClientError {
 public:
  UnknownTarget(std::string name, std::vector<std::string> suggestions, std::string detail = "");
  const std::string& name() const { return name_; }
  const std::vector<std::string>& suggestions() const { return suggestions_; }

 private:
  std::string name_;
  std::vector<std::string> suggestions_;
};

// The sim answered "not accepted".
class Refused : public ClientError {
 public:
  Refused(std::string target, std::string reason, int64_t request_id);
  const std::string& target() const { return target_; }
  const std::string& reason() const { return reason_; }
  int64_t request_id() const { return request_id_; }

 private:
  std::string target_, reason_;
  int64_t request_id_;
};

// Something awaited did not come in time (a reply, a sim time, a reading).
class Timeout : public ClientError {
 public:
  // hint: what may explain it ("the sim is paused: ..."), appended.
  Timeout(std::string awaited, double seconds, std::string url, std::string hint = "");
  const std::string& awaited() const { return awaited_; }
  double seconds() const { return seconds_; }

 private:
  std::string awaited_;
  double seconds_;
};

// No SIM_MODEL on the bus: no sim runs there (or it cannot be reached).
// seconds 0: a client made with learn_model = false was asked for a name
// before any Relearn().
class NoSim : public ClientError {
 public:
  // hint: what may explain it (the bus's signing), appended.
  NoSim(std::string url, double seconds, std::string hint = "");
  const std::string& url() const { return url_; }
  double seconds() const { return seconds_; }

 private:
  std::string url_;
  double seconds_;
};

// The sim under the client has a new simulation id (restarted or reset):
// names, indices and pending replies of the old one no longer hold.
class SimRestarted : public ClientError {
 public:
  SimRestarted(int64_t old_simulation_id, int64_t new_simulation_id);
  int64_t old_simulation_id() const { return old_id_; }
  int64_t new_simulation_id() const { return new_id_; }

 private:
  int64_t old_id_, new_id_;
};

// The sim ended (its duration reached, or told to quit): a lock-step loop
// ends with it. step: where it stopped.
class SimStopped : public ClientError {
 public:
  explicit SimStopped(int64_t step);
  int64_t step() const { return step_; }

 private:
  int64_t step_;
};

// Lock-step (lock_step.h): the sim refused a JOIN, LEAVE or done mark, or
// released this controller (it did not answer a tick within the sim's
// lockStepTimeout). tick: the tick concerned, -1 when none.
class LockStepError : public ClientError {
 public:
  LockStepError(std::string controller, std::string what, int64_t tick);
  const std::string& controller() const { return controller_; }
  int64_t tick() const { return tick_; }

 private:
  std::string controller_;
  int64_t tick_;
};

// Values that do not fit the target before anything is sent.
class BadValues : public ClientError {
 public:
  BadValues(std::string target, std::string field, std::string value, std::string expected);
  const std::string& target() const { return target_; }
  const std::string& field() const { return field_; }
  const std::string& value() const { return value_; }
  const std::string& expected() const { return expected_; }

 private:
  std::string target_, field_, value_, expected_;
};

}  // namespace simpartner::client
