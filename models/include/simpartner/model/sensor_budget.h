// What a robot's sensors put on the bus together: its scanners' and
// lidars' rays and its cameras' pixels a second. A robot is held to the
// bound of one sensor (model.h says why the bounds are what the bus
// carries beside the states): twenty lidars each within the bound once
// put 18.6 MB/s on SIM_SENSOR and slowed the sim to 0.6x real time. The
// loader checks a robot file; the sim checks each SENSOR_PARAMS command.
#pragma once

#include <string>
#include <vector>

#include "simpartner/model/model.h"

namespace simpartner::model {

inline constexpr double kMaxRobotRaysPerSecond = kMaxScannerRaysPerSecond;
inline constexpr double kMaxRobotPixelsPerSecond = kMaxCameraPixelsPerSecond;

// Rays one reading casts: a Scanner's rays (as its file gives them), a
// Lidar's rays x layers; 0 for the other kinds.
double RaysPerReading(const Sensor& sensor);

// What one sensor sends a second (rays or pixels).
struct SensorLoad {
  std::string sensor;
  double per_second;
};

// "" when the loads sum to at most limit; else the refusal, naming the
// robot, the sum, the largest loads and the bound. kinds: "scanners and
// lidars" or "cameras"; unit: "rays/s" or "pixels/s".
std::string BudgetExcess(const std::string& robot, const std::vector<SensorLoad>& loads,
                         double limit, const std::string& kinds, const std::string& unit);

// The robot's rays and pixels a second at its file's rates, each over its
// bound as BudgetExcess words it; empty when both are within.
std::vector<std::string> RobotBudgetExcesses(const Robot& robot);

}  // namespace simpartner::model
