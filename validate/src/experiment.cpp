#include "simpartner/validate/experiment.h"

#include <chrono>
#include <exception>
#include <limits>

#include "simpartner/diagnostic.h"

namespace simpartner::validate {

bool ExperimentResult::Passed() const {
  if (!error.empty() || checks.empty()) return false;
  for (const Check& c : checks)
    if (!c.pass) return false;
  return true;
}

double StepTiming::MicrosecondsPerStep() const {
  return steps > 0 ? seconds * 1e6 / static_cast<double>(steps)
                   : std::numeric_limits<double>::quiet_NaN();
}

double ExperimentResult::Measured(const std::string& label) const {
  for (const Check& c : checks)
    if (c.label.rfind(label, 0) == 0) return c.measured;
  throw Error("experiment '" + name + "' has no check labelled '" + label + "'" +
              (error.empty() ? std::string() : " (it failed: " + error + ")"));
}

const std::vector<Experiment>& Experiments() {
  static const std::vector<Experiment> kExperiments = {
      {"free_fall", "Free fall from 500 m, dt 0.02 to 0.001 s, g 9.81 and 50", false, FreeFall},
      {"free_fall_thrown", "Body with velocity (10, 10, 0) falling", false, FreeFallThrown},
      {"sliding_cube", "1 m, 1 kg cube sliding from 10 m/s", false, SlidingCube},
      {"two_spheres", "Two spheres r 0.5, equal and opposite velocities", false, TwoSpheres},
      {"circle_equal", "gen1 circle, alpha 0.2972 rad, equal wheel speeds, mu 0.5 and 1.0",
       false, CircleEqualSpeeds},
      {"circle_differential", "gen1 circle, alpha 0.2 rad, inner wheels 1.00 m/s, outer 1.10 m/s",
       false, CircleDifferentialSpeeds},
      {"scanner", "gen2 scanner, wall 5.335 m ahead, torso turning at 0.01 rad/s", false, Scanner},
      {"pole_task", "gen3 picks up a 5 kg pole, carries it and sets it on two other cubes", false,
       PoleTask},
      {"skid", "gen1 18 kg on mu 0.025, wheels at 1 rad/s", true, SkiddingWheels},
      {"caterpillar", "gen1 18 kg on mu 0.025, caterpillar gait", true, CaterpillarGait},
      {"rolking", "gen1 18 kg on mu 0.025, rolling walking (rolking)", true, RollingWalking},
      {"gen4_loads", "gen4 static wheel loads vs the real robot", false, Gen4StaticLoads},
      {"test_track", "gen4 on the heightfield test track, wheels at 1.5 rad/s", true, TestTrack},
      {"rolling_sphere", "Beyond the original: a sphere rolling on flat ground comes to rest",
       false, RollingSphere},
      {"pendulum_energy", "Beyond the original: a passive pendulum creates no energy in 60 s",
       false, PendulumEnergy},
      {"soil_sinkage", "On soil: a rigid wheel's static sinkage on four soils, two loads",
       false, SoilSinkage},
      {"soil_compaction", "On soil: a towed wheel's compaction resistance", false,
       SoilCompaction},
      {"soil_traction", "On soil: a driven wheel's drawbar pull against slip 0.05 to 0.6", false,
       SoilTraction},
      {"soil_step_size", "On soil: sinkage and drawbar pull at 0.5, 1 and 2 ms steps",
       false, SoilStepSize},
      {"soil_multipass", "On soil: a second wheel in the first one's rut sinks less", false,
       SoilMultiPass},
      {"soil_robot", "On soil: gen3 driven on dry sand and snow vs hard ground", false,
       SoilRobot},
      {"soil_measured", "On soil: a small wheel on sand against measured single-wheel tests",
       false, SoilMeasured},
      {"sensors", "Field sensors: IMU, encoder, lidar and GNSS on a turntable rig", false, Sensors},
  };
  return kExperiments;
}

const Experiment* FindExperiment(const std::string& name) {
  for (const Experiment& e : Experiments())
    if (e.name == name) return &e;
  return nullptr;
}

ExperimentResult RunExperiment(const Experiment& experiment, const Context& context) {
  Context own = context;
  if (context.progress)
    own.progress = [&](const std::string& line) { context.progress(experiment.name + ": " + line); };
  StepTiming stepping;
  own.step_timing = &stepping;
  const auto start = std::chrono::steady_clock::now();
  ExperimentResult result;
  try {
    result = experiment.run(own);
  } catch (const std::exception& e) {
    result = ExperimentResult{};
    result.error = e.what();
  }
  result.name = experiment.name;
  result.title = experiment.title;
  result.engine = context.params.engine;
  result.stepping = stepping;
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace simpartner::validate
