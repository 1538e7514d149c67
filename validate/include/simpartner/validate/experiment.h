// The validation experiments of SPEC 8, ours beyond them, the soil
// experiments and the field sensors' rig: each runs a shipped world (the
// soil rigs: a world of its own beside them) through the sim library
// (sp_sim_core) exactly as simpartner-sim would, drives the robot with timed commands and
// compares what happened with the analytic or real-robot target.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "simpartner/parameters.h"
#include "simpartner/validate/check.h"
#include "simpartner/validate/plot.h"

namespace simpartner::validate {

// Gravity as the shipped worlds give it [m/s^2], and WorkPartner's wheel
// radius on every generation (SPEC 7) [m].
inline constexpr double kGravity = 9.81;
inline constexpr double kWheelRadius = 0.235;

// Wall time of an experiment's sim steps: Simulation::Step alone, without
// the analysis between the steps.
struct StepTiming {
  int64_t steps = 0;
  double seconds = 0.0;
  // Mean wall time of one step [µs]; NaN without steps.
  double MicrosecondsPerStep() const;
};

// What an experiment needs from the caller.
struct Context {
  std::string models_dir;   // holds worlds/ and robots/
  // The run's parameters (defaults + parameters.txt + overrides);
  // params.engine is the physics engine every SimRun of it uses.
  Parameters params;
  // Called with a line of progress now and then during long runs; may be empty.
  std::function<void(const std::string&)> progress;
  // Shorter runs of the same experiments with the same tolerances (the
  // unit tests): fewer laps, a shorter scan.
  bool quick = false;
  // Where every SimRun of the experiment adds its steps' wall time; may be
  // null (RunExperiment sets its own).
  StepTiming* step_timing = nullptr;
};

struct ExperimentResult {
  std::string name;
  std::string title;
  std::string engine;         // the physics engine it ran on: "ode", "mujoco"
  std::vector<Check> checks;
  std::vector<Plot> plots;
  // Markdown for the report: how it was run and what the figures mean;
  // where a target is physically wrong, why.
  std::string notes;
  double sim_seconds = 0.0;   // simulated time over all its runs
  double wall_seconds = 0.0;
  StepTiming stepping;        // the sim steps alone, over all its runs
  std::string error;          // set when the run itself failed (exploded, bad file)
  // Set when the engine cannot represent the experiment's world (what the
  // engine says it lacks, e.g. soil on MuJoCo): neither passed nor failed,
  // and left out of the engine's tally.
  std::string not_applicable;

  bool Passed() const;
  // Measured value of the check whose label starts with `label`; throws
  // simpartner::Error when there is none.
  double Measured(const std::string& label) const;
};

struct Experiment {
  std::string name;         // for --only, e.g. "free_fall"
  std::string title;        // the SPEC 8 row
  bool slow = false;        // minutes of simulated time (long gaits, test track)
  std::function<ExperimentResult(const Context&)> run;
};

// Every experiment, in the order of SPEC 8, then ours.
const std::vector<Experiment>& Experiments();
const Experiment* FindExperiment(const std::string& name);

// Runs one experiment on context.params.engine: fills name, title, engine,
// wall time and the steps' wall time, and turns an exception (an explosion, a rejected command,
// a broken file, an engine refusing the world) into a failed result with
// the reason.
ExperimentResult RunExperiment(const Experiment& experiment, const Context& context);

// The experiments one by one (SPEC 8 order).
ExperimentResult FreeFall(const Context& context);
ExperimentResult FreeFallThrown(const Context& context);
ExperimentResult SlidingCube(const Context& context);
ExperimentResult TwoSpheres(const Context& context);
ExperimentResult CircleEqualSpeeds(const Context& context);
ExperimentResult CircleDifferentialSpeeds(const Context& context);
ExperimentResult Scanner(const Context& context);
ExperimentResult PoleTask(const Context& context);
ExperimentResult SkiddingWheels(const Context& context);
ExperimentResult CaterpillarGait(const Context& context);
ExperimentResult RollingWalking(const Context& context);
ExperimentResult Gen4StaticLoads(const Context& context);
ExperimentResult TestTrack(const Context& context);
ExperimentResult RollingSphere(const Context& context);
ExperimentResult PendulumEnergy(const Context& context);
// A single rigid wheel on soil (experiments_soil.cpp), ODE only.
ExperimentResult SoilSinkage(const Context& context);
ExperimentResult SoilCompaction(const Context& context);
ExperimentResult SoilTraction(const Context& context);
ExperimentResult SoilStepSize(const Context& context);
ExperimentResult SoilMultiPass(const Context& context);
ExperimentResult SoilMeasured(const Context& context);
// gen3 on the shipped soil worlds (experiments_soil_robot.cpp).
ExperimentResult SoilRobot(const Context& context);
// The field sensors on the sensor rig (experiments_sensors.cpp).
ExperimentResult Sensors(const Context& context);

}  // namespace simpartner::validate
