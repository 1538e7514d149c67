#include "simpartner/model/sensor_budget.h"

#include <algorithm>

#include "simpartner/model/sensor_parameters.h"
#include "simpartner/text.h"

namespace simpartner::model {
namespace {

// The loads a refusal names one by one; the rest are counted.
constexpr size_t kLoadsNamed = 3;

}  // namespace

double RaysPerReading(const Sensor& sensor) {
  switch (sensor.kind) {
    case SensorKind::kScanner:
      return sensor.rays;
    case SensorKind::kLidar:
      return sensor.parameters[lidar_param::kRays] * sensor.parameters[lidar_param::kLayers];
    default:
      return 0.0;
  }
}

std::string BudgetExcess(const std::string& robot, const std::vector<SensorLoad>& loads,
                         double limit, const std::string& kinds, const std::string& unit) {
  double sum = 0.0;
  for (const SensorLoad& load : loads) sum += load.per_second;
  if (sum <= limit) return "";
  std::vector<SensorLoad> largest = loads;
  std::stable_sort(largest.begin(), largest.end(), [](const SensorLoad& a, const SensorLoad& b) {
    return a.per_second > b.per_second;
  });
  std::string named;
  for (size_t k = 0; k < largest.size() && k < kLoadsNamed; ++k)
    named += (k == 0 ? "" : ", ") + largest[k].sensor + " " +
             FormatNumber(largest[k].per_second, 10);
  if (largest.size() > kLoadsNamed)
    named += " and " + std::to_string(largest.size() - kLoadsNamed) + " more";
  return "robot '" + robot + "': its " + kinds + " together send " + FormatNumber(sum, 10) +
         " " + unit + " (" + named + "), more than the " + FormatNumber(limit, 10) + " " + unit +
         " one robot may put on the bus (models/.../sensor_budget.h says why)";
}

std::vector<std::string> RobotBudgetExcesses(const Robot& robot) {
  std::vector<SensorLoad> rays;
  std::vector<SensorLoad> pixels;
  for (const Sensor& s : robot.sensors) {
    if (RaysPerReading(s) > 0.0) rays.push_back({s.name, s.rate * RaysPerReading(s)});
    if (s.kind == SensorKind::kCamera)
      pixels.push_back({s.name, s.rate * s.camera.width * s.camera.height});
  }
  std::vector<std::string> excesses;
  for (std::string excess :
       {BudgetExcess(robot.model_name, rays, kMaxRobotRaysPerSecond, "scanners and lidars",
                     "rays/s"),
        BudgetExcess(robot.model_name, pixels, kMaxRobotPixelsPerSecond, "cameras",
                     "pixels/s")})
    if (!excess.empty()) excesses.push_back(std::move(excess));
  return excesses;
}

}  // namespace simpartner::model
