// Teleop's connection to the sim: learns the model (and again after a
// restart), picks the mapping for the robot's model, applies the safety
// rules and sends the paced commands. The front ends (gamepad, keyboard
// window, the test build's virtual pad) call Tick with the input of the
// moment, from one thread.
#pragma once

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "simpartner/client/client.h"
#include "simpartner/teleop/mapping.h"
#include "simpartner/teleop/teleop.h"

namespace simpartner::teleop {

struct SessionOptions {
  std::string url = client::kDefaultUrl;
  std::string program = "teleop";
  // A mapping file given by the user (--mapping); "" = the shipped one for
  // the robot's model from mapping_dir.
  std::string mapping_file;
  std::string mapping_dir;
  double period = 0.1;  // [s] between command batches, at least
  // Override the mapping's full-stick wheel speed [rad/s] and steer angle
  // [rad] (magnitudes; the mapping's signs stay). NaN: the mapping's.
  double max_speed = NAN;
  double max_steer = NAN;
};

class Session {
 public:
  // Connects (no sim needed yet: the model is learned in Tick). Throws
  // client::ClientError for a bad URL.
  Session(SessionOptions options, std::ostream& log);
  ~Session();

  // One pass: follow a restart, decide the demand, send when due.
  // `stopping`: SIGINT/SIGTERM came (commands the stop, see StopAndFlush).
  void Tick(const InputState& input, bool stopping = false);
  // Sends the stop batch (zero wheels, holds) as soon as the pacing
  // allows (within one period) and returns: for exit on a signal.
  void StopAndFlush(const InputState& input);

  // "gen3 | moving | wheels +1.20 rad/s | steer -0.10 rad | sim running x1.00"
  std::string StatusLine() const;
  const Demand& demand() const { return demand_; }
  const Controller* controller() const { return controller_.get(); }
  int64_t batches_sent() const { return batches_; }

 private:
  double Now() const;
  void Learn();
  void Adopt(const model_t& model);
  void Send(const Pacer::Batch& batch);

  SessionOptions options_;
  std::ostream& log_;
  std::unique_ptr<client::Client> client_;
  std::unique_ptr<Controller> controller_;
  Pacer pacer_;
  Demand demand_;
  int64_t simulation_id_ = 0;
  int64_t failed_simulation_id_ = -1;  // whose mapping did not fit (said once)
  double next_learn_ = 0;
  int64_t batches_ = 0;
  std::string robot_model_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace simpartner::teleop
