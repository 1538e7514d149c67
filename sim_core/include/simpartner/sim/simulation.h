// One simulated world: the physics engine (ODE or MuJoCo), the actuator controllers, the sensors,
// the step counter and the health check. No transport: the node feeds it
// decoded commands and publishes what it returns, so tests drive it directly.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/model/model.h"
#include "simpartner/model_t.hpp"
#include "simpartner/parameters.h"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/sim/command_queue.h"
#include "simpartner/sim/controllers.h"
#include "simpartner/model/flat_model.h"
#include "simpartner/sim/engine.h"
#include "simpartner/sim/sensor_readings.h"
#include "simpartner/sim/soil_ruts.h"
#include "simpartner/state_t.hpp"
#include "simpartner/warning_t.hpp"

namespace simpartner::sim {

class Simulation {
 public:
  // Bounds of the queue of accepted commands waiting for their step.
  static constexpr size_t kMaxPendingCommands = CommandQueue::kMaxCommands;
  static constexpr size_t kMaxPendingBytes = CommandQueue::kMaxBytes;
  // Readings nobody takes (a program stepping a Simulation without
  // publishing) are kept up to this many; beyond it the older half goes.
  static constexpr size_t kMaxUntakenReadings = 8192;

  Simulation(model::World world, Parameters params, int64_t simulation_id);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  int64_t step() const { return step_; }
  // Simulation time = step count x step size (never accumulated).
  double time() const { return static_cast<double>(step_) * params_.stepsize; }
  bool faulted() const { return faulted_; }
  int64_t simulation_id() const { return simulation_id_; }
  const model::FlatModel& flat() const { return flat_; }
  const model::World& world() const { return world_; }
  const Parameters& params() const { return params_; }
  // The engine itself (tests, benches): what it is told may change the
  // bodies, so the readouts kept from the last step are read again.
  PhysicsEngine& engine() {
    bodies_read_ = false;
    return *engine_;
  }
  const ActuatorController& controller(int actuator) const {
    return controllers_[static_cast<size_t>(actuator)];
  }

  // Back to the initial state of the files with a new simulation id; pending
  // commands are dropped and every actuator holds again.
  void Reset(int64_t simulation_id);

  // Checks a command now. A rejected one gets its reply at once (returned);
  // an accepted one is queued for its step and replied to when applied.
  std::optional<command_reply_t> Submit(const command_t& command);

  // Applies the commands due, runs the controllers, steps the engine once
  // and checks the state. Returns false (and takes no step) once faulted.
  bool Step();

  // What the last steps produced, for the node to publish.
  std::vector<command_reply_t> TakeReplies();
  std::vector<sensor_reading_t> TakeSensorReadings();
  std::vector<warning_t> TakeWarnings();

  void FillState(state_t* state) const;
  // The ruts of the wheels on soil so far (SIM_SOIL_RUTS); cleared by a reset.
  SoilRuts& ruts() { return ruts_; }
  void FillModel(model_t* model) const;
  sensor_reading_t ReadSensor(int sensor);

 private:
  struct SensorState {
    double rate = 0.0;
    int rays = 11;
    double half_span = 0.1;
    double range = 10.0;
    std::string echo_text;
    int64_t period_steps = 0;     // 0 = on request only
    bool imu = false;             // keeps imu_memory up to date every step
    ImuMemory imu_memory;
  };

  void Build();
  // A robot on soil set down before step 0 (simulation_settle.cpp): it
  // starts at rest at the sinkage its weight gives, not at the surface.
  void SettleOnSoil();
  // The joint controllers' motor settings for the coming step.
  void UpdateControllers();
  // One engine step; false when the engine gave up, which pauses the sim
  // (faulted_) with an error naming its message, then `then`.
  bool StepEngine(const std::string& then);
  // The engine's messages of its last step, as warnings.
  void SayEngineMessages();
  command_reply_t Reply(const command_t& command, bool accepted, const std::string& reason) const;
  void ApplyPending(const PendingCommand& pending);
  // Why robot's scanners and lidars at their present rates cast more rays
  // than a robot may (model::BudgetExcess); "" when they do not.
  std::string RobotRaysExcess(int robot) const;
  // Every body's readout after a step, kept for the health check and
  // FillState (reading a MuJoCo body's velocity is a transform), and the
  // wheels' on soil.
  void ReadBodies();
  void FillWheelSoil(state_t* state) const;
  void CheckHealth();
  // What a reading of sensor `index` at this step is made from.
  SensorInput SensorInputOf(int index);
  // The reading's values, by the sensor's kind.
  std::vector<double> ReadValues(const SensorInput& in, const SensorState& state);
  void RememberImuVelocities();
  void WalkImuBiases();
  void AddWarning(int8_t severity, const std::string& source, const std::string& message,
                  std::vector<std::string> bodies = {});

  model::World world_;
  Parameters params_;
  model::FlatModel flat_;
  int64_t simulation_id_;
  std::unique_ptr<PhysicsEngine> engine_;
  std::vector<BodyReadout> bodies_;  // after the last step, when bodies_read_
  std::vector<WheelSoilReadout> wheel_soil_;  // after the last step, when bodies_read_
  bool bodies_read_ = false;
  SoilRuts ruts_;
  std::vector<ActuatorController> controllers_;
  std::vector<SensorState> sensors_;
  CommandQueue pending_;
  int64_t step_ = 0;
  bool faulted_ = false;
  std::vector<command_reply_t> replies_;
  std::vector<sensor_reading_t> readings_;
  std::vector<int> read_requests_;
  std::vector<warning_t> warnings_;
  SensorNoise noise_;
};

}  // namespace simpartner::sim
