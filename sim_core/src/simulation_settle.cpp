// A robot on soil set down before step 0 (docs/soil.md, "A robot set on
// soil starts at rest"). The files place a robot with its wheels on the
// untouched surface; left to fall, each wheel would overshoot its sinkage
// and rest on the soil's unloading line, not on Bekker's curve, after
// seconds of bouncing. So the sim lowers it first, quasi-statically:
//   - its weight comes on over kRampSeconds (a force against gravity on
//     every moving body, falling from m g to 0), so the soil is loaded
//     along Bekker's curve and never unloaded;
//   - every moving body is damped, -m v / kDampingSeconds (about critical
//     for a robot on sand), so nothing overshoots;
//   - once every body has been slower than kSettledSpeed for kSettledSeconds
//     (at most kLongestSeconds in all), every velocity is set to 0.
// The state that follows is step 0: the robot at rest at each wheel's
// static sinkage, the soil holding the ruts it pressed. The settle takes
// no sim time, sends nothing, and is the same on every run; soilSettle=0
// drops the robot from where the file puts it instead.
#include <algorithm>
#include <cmath>

#include "simpartner/sim/simulation.h"
#include "simpartner/text.h"

namespace simpartner::sim {
namespace {

constexpr double kRampSeconds = 0.5;
constexpr double kDampingSeconds = 0.02;
constexpr double kSettledSpeed = 1e-4;  // [m/s]
constexpr double kSettledSeconds = 0.1;
constexpr double kLongestSeconds = 10.0;

// Whether the file sets anything moving: then its start is the user's.
bool AnythingMoves(const model::FlatModel& flat) {
  for (const model::FlatBody& body : flat.bodies)
    if (!body.linear_velocity.isZero() || !body.angular_velocity.isZero()) return true;
  return false;
}

int Steps(double seconds, double stepsize) {
  return std::max(1, static_cast<int>(std::lround(seconds / stepsize)));
}

}  // namespace

void Simulation::SettleOnSoil() {
  if (!params_.soilSettle || world_.robots.empty() || !world_.HasSoilGround() || AnythingMoves(flat_))
    return;
  const double h = params_.stepsize;
  const int ramp = Steps(kRampSeconds, h), still_needed = Steps(kSettledSeconds, h);
  const int longest = Steps(kLongestSeconds, h);
  int still = 0, k = 0;
  for (; k < longest && still < still_needed; ++k) {
    const double carried = k < ramp ? 1.0 - static_cast<double>(k) / ramp : 0.0;
    double fastest = 0.0;
    for (size_t b = 0; b < flat_.bodies.size(); ++b) {
      const model::Body& body = *flat_.bodies[b].source;
      if (body.is_static) continue;
      const Eigen::Vector3d v = engine_->ReadBody(static_cast<int>(b)).linear_velocity;
      fastest = std::max(fastest, v.norm());
      engine_->AddForce(static_cast<int>(b),
                        -body.mass * (carried * world_.gravity + v / kDampingSeconds));
    }
    still = k >= ramp && fastest < kSettledSpeed ? still + 1 : 0;
    UpdateControllers();
    if (!StepEngine(" while the robot settled on soil; reset to go on")) return;
    SayEngineMessages();
  }
  engine_->ZeroVelocities();
  ReadBodies();
  ruts_.Stamp(wheel_soil_);
  AddWarning(warning_t::SEVERITY_INFO, "soil",
             "settled on soil in " + std::to_string(k) + " steps before step 0" +
                 (still < still_needed ? " (still moving after " + FormatFixed(kLongestSeconds, 0) +
                                             " s: it starts so)"
                                       : ""));
}

}  // namespace simpartner::sim
