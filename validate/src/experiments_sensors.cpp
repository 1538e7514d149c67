// The field sensors against closed forms, on any engine: the
// shipped sensor rig (models/worlds/sensor_rig.xml) at rest, then its
// table turned at 2 rad/s (sequences/sensor_rig_spin.xml).
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/validate/analysis.h"
#include "simpartner/validate/experiment.h"
#include "simpartner/validate/sim_run.h"

namespace simpartner::validate {
namespace {

constexpr double kSpinStart = 1.0, kOmega = 2.0;  // sensor_rig_spin.xml
constexpr double kImuRadius = 0.8;                // TableImu, sensor_turntable.xml
constexpr double kCountsPerTurn = 2048;           // SpindleEncoder
// BaseImu's white noise densities and biases, and its rate.
constexpr double kAccelDensity = 0.002, kAccelBiasX = 0.05;
constexpr double kGyroDensity = 0.0005, kGyroBiasZ = 0.001, kImuRate = 100;
constexpr double kGnssHorizontal = 2, kGnssVertical = 4;
// The lidar: at the base's centre (0.5 m up, less the contact's sag), 4 m
// from the wall's face; its rays and layers.
constexpr double kWallDistance = 4.0;
constexpr int kRays = 9, kLayers = 4;
constexpr double kHalfSpan = 0.4, kLowest = -0.3, kHighest = 0.3;

// Readings of one sensor by sim time.
using Samples = std::vector<std::pair<double, std::vector<double>>>;

double Spread(const std::vector<double>& v) {
  const double mean = Mean(v);
  double sum = 0;
  for (const double x : v) sum += (x - mean) * (x - mean);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

std::vector<double> Column(const Samples& samples, size_t k, double from, double to) {
  std::vector<double> out;
  for (const auto& [t, values] : samples)
    if (t >= from && t <= to) out.push_back(values[k]);
  return out;
}

// The lidar's closed form: a ray at elevation e and azimuth a meets the
// wall at 4 / (cos e cos a), or first, looking down, the floor at
// height / sin(-e).
double LidarRange(int layer, int ray, double height) {
  const double e = kLowest + (kHighest - kLowest) * layer / (kLayers - 1);
  const double a = -kHalfSpan + 2 * kHalfSpan * ray / (kRays - 1);
  const double wall = kWallDistance / (std::cos(e) * std::cos(a));
  return e < 0 ? std::min(wall, height / std::sin(-e)) : wall;
}

void CheckNoise(const Samples& imu, double end, ExperimentResult* result) {
  // The samples of a white noise of density d at rate f have the spread
  // d sqrt(f); a mean of N is within 3 sigma / sqrt(N) of the bias and
  // the spread within 3 / sqrt(2 N) of itself (three standard errors).
  struct Axis {
    const char* what;
    size_t column;
    double density, bias;
    const char* unit;
  };
  for (const Axis& axis : {Axis{"BaseImu acceleration x", 0, kAccelDensity, kAccelBiasX, "m/s^2"},
                           Axis{"BaseImu rate z", 5, kGyroDensity, kGyroBiasZ, "rad/s"}}) {
    const std::vector<double> v = Column(imu, axis.column, 0.1, end);
    const double n = static_cast<double>(v.size());
    const double sigma = axis.density * std::sqrt(kImuRate);
    // At rest the base feels no force along x and turns about no axis:
    // the mean is the bias alone.
    result->checks.push_back(Absolute(std::string(axis.what) + ": mean of " +
                                          FormatNumber(n) + " vs its bias",
                                      Mean(v), axis.bias, 3 * sigma / std::sqrt(n), axis.unit));
    result->checks.push_back(Relative(std::string(axis.what) + ": spread vs density sqrt(rate)",
                                      Spread(v), sigma, 3 / std::sqrt(2 * n), axis.unit));
  }
}

}  // namespace

ExperimentResult Sensors(const Context& context) {
  ExperimentResult result;
  SimRun run(context, "sensor_rig.xml");
  run.PlaySequence("sensor_rig_spin.xml");
  const double end = context.quick ? 11.0 : kSpinStart + 100.0;
  std::map<std::string, Samples> readings;
  int encoder_checked = 0, encoder_wrong = 0;
  const int spindle = run.Joint("Spindle");
  run.RunUntil(end, [&] {
    for (sensor_reading_t& r : run.sim().TakeSensorReadings()) {
      if (r.name == "SpindleEncoder") {
        const double angle = run.sim().engine().ReadJoint(spindle).continuous_position[0];
        ++encoder_checked;
        encoder_wrong += r.values[0] != std::floor(angle * kCountsPerTurn / (2 * M_PI));
        continue;
      }
      readings[r.name].emplace_back(r.sim_time, std::move(r.values));
    }
  });
  result.sim_seconds = run.time();
  for (const char* sensor : {"TableImu", "BaseImu", "Gnss", "Lidar"})
    if (readings[sensor].empty()) throw Error(std::string("sensor_rig.xml: no reading of ") + sensor);
  const Samples& table = readings["TableImu"];
  // At rest the table IMU reads +g up and nothing else; turning, omega
  // about the spindle (its y) and omega^2 r toward the axis (its -x). The
  // IMU differentiates its velocity over a sample (10 ms): the chord
  // shortens omega^2 r by (omega dt)^2 / 6 = 7e-5 of it.
  result.checks.push_back(Absolute("TableImu at rest: specific force up vs g",
                                   Mean(Column(table, 1, 0.2, kSpinStart - 0.1)), kGravity, 1e-3,
                                   "m/s^2"));
  const double late = end - 2.0;
  result.checks.push_back(Relative("TableImu turning: rate about the spindle vs omega",
                                   Mean(Column(table, 4, late, end)), kOmega, 1e-4, "rad/s"));
  result.checks.push_back(Relative("TableImu turning: acceleration toward the axis vs omega^2 r",
                                   -Mean(Column(table, 0, late, end)), kOmega * kOmega * kImuRadius,
                                   1e-3, "m/s^2"));
  result.checks.push_back(AtMost("SpindleEncoder readings off floor(angle cpr / 2 pi), of " +
                                     FormatNumber(encoder_checked),
                                 encoder_wrong, 0, ""));
  const std::vector<double>& scan = readings["Lidar"].back().second;
  const double lidar_height = run.Position(run.Body("Base")).y();
  for (int layer = 0; layer < kLayers; ++layer) {
    double worst = 0;
    for (int ray = 0; ray < kRays; ++ray)
      worst = std::max(worst, std::abs(scan[static_cast<size_t>(layer * kRays + ray)] -
                                       LidarRange(layer, ray, lidar_height)));
    result.checks.push_back(AtMost("Lidar layer " + std::to_string(layer) +
                                       ": largest error over its rays (wall or floor)",
                                   worst, 1e-6, "m"));
  }
  CheckNoise(readings["BaseImu"], end, &result);
  const Samples& gnss = readings["Gnss"];
  const double n = static_cast<double>(gnss.size());
  const double up = run.Position(run.Body("Base")).y();
  result.checks.push_back(Absolute("Gnss: mean east of " + FormatNumber(n) + " fixes vs the truth",
                                   Mean(Column(gnss, 1, 0, end)), 0.0,
                                   3 * kGnssHorizontal / std::sqrt(n), "m"));
  result.checks.push_back(Absolute("Gnss: mean north vs the truth", Mean(Column(gnss, 2, 0, end)),
                                   0.0, 3 * kGnssHorizontal / std::sqrt(n), "m"));
  result.checks.push_back(Absolute("Gnss: mean up vs the antenna's height",
                                   Mean(Column(gnss, 3, 0, end)), up,
                                   3 * kGnssVertical / std::sqrt(n), "m"));

  Plot plot;
  plot.file = "sensors.png";
  plot.title = "TableImu on the turntable (2 rad/s from t = 1 s, r 0.8 m)";
  plot.xlabel = "t [s]";
  plot.ylabel = "[rad/s], [m/s^2]";
  Series rate{"rate about the spindle", {}, {}, "lines"};
  Series centripetal{"acceleration toward the axis", {}, {}, "lines"};
  for (const auto& [t, v] : table) {
    if (t > kSpinStart + 4.0) break;
    rate.x.push_back(t);
    rate.y.push_back(v[4]);
    centripetal.x.push_back(t);
    centripetal.y.push_back(-v[0]);
  }
  plot.series = {rate, centripetal,
                 Series{"omega", {0, kSpinStart + 4}, {kOmega, kOmega}, "dashed"},
                 Series{"omega^2 r", {0, kSpinStart + 4}, {kOmega * kOmega * kImuRadius,
                                                           kOmega * kOmega * kImuRadius},
                        "dashed"}};
  result.plots.push_back(plot);
  result.notes =
      "The shipped sensor rig (`sensor_rig.xml`, `robots/sensor_turntable.xml`): a table on a "
      "hinge on a 1000 kg base, at rest for 1 s, then turned at 2 rad/s by its motor "
      "(`sequences/sensor_rig_spin.xml`). Closed forms: the noise-free TableImu, 0.8 m off the "
      "axis, reads +g up at rest and, turning, omega about the spindle and omega^2 r toward the "
      "axis (its finite difference over a 10 ms sample shortens that by 7e-5); the encoder "
      "reads floor(angle 2048 / 2 pi) through every turn; the lidar, 0.5 m up and 4 m from a "
      "wall, reads 4 / (cos e cos a) on each ray, or in its lowest layer (e = -0.3 rad) the "
      "floor at 0.5 / sin 0.3 first; the BaseImu's white noise (0.002 m/s^2/sqrt(Hz), 0.0005 "
      "rad/s/sqrt(Hz) at 100 Hz) has the spread d sqrt(f), and its mean is the configured "
      "bias; the GNSS fixes (2 m horizontal, 4 m vertical) average to the antenna's place. "
      "Statistical tolerances are three standard errors of the samples taken (" +
      FormatNumber(static_cast<double>(readings["BaseImu"].size())) +
      " IMU samples; the unit tests take fewer). tests/sim_core/sensors_test.cpp checks the "
      "same and more (free fall, bias random walk, dropouts, cover) on both engines.";
  return result;
}

}  // namespace simpartner::validate
