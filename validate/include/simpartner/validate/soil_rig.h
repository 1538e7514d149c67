// The single-wheel rigs of terramechanics, as worlds written
// here, read by the loader beside the shipped worlds (so that their
// <soil library=...> is the shipped models/soils/wong2008.xml) and run
// through the sim library. The wheel is a Cylinder of radius 0.3 m and
// width 0.2 m on a surface of soil; y is up.
#pragma once

#include <string>

#include "simpartner/model/model.h"
#include "simpartner/validate/experiment.h"

namespace simpartner::validate {

inline constexpr double kRigRadius = 0.3, kRigWidth = 0.2, kRigGravity = 9.81;

// A soil of the shipped library by name, with figures the experiment
// changes written as the world's overrides ("<viscosity>60</viscosity>").
struct RigSoil {
  std::string name;
  std::string overrides;
};

// A wheel standing free on the soil, lowered onto it.
struct StandingRun {
  double sinkage = 0;  // of the lowest rim point at the end [m]
  double drift = 0;    // horizontal distance it moved [m]
  double sim_seconds = 0;
};

// A wheel of `mass` [kg] held above its resting place by a support force
// falling from its weight to 0 over 2 s, then left 1 s. Empty
// `not_applicable` unless context's engine cannot model the soil.
StandingRun RunStandingWheel(const Context& context, const RigSoil& soil, double mass,
                             double stepsize, std::string* not_applicable);

// The rig: a sled on a rail along x, its speed held by the rail's motor;
// per wheel a carrier on a free vertical slider below the sled (the
// wheel carries its own and its carrier's weight, `load`), the wheel on an
// axle in it. Tandem: a second wheel `spacing` behind the first, in its
// track.
struct RigSetup {
  RigSoil soil;
  double load = 490.5;  // per wheel [N]
  bool tandem = false;
  double spacing = 0.8;  // [m]
  double speed = 0.3;    // the sled's [m/s]
  bool driven = true;    // axles spun at speed / ((1 - slip) r); false: free (towed)
  double slip = 0.0;  // i: 1 - v / (r omega) driving (>= 0), r omega / v - 1 braking (< 0)
  double stepsize = 0.001;
  double drive_seconds = 3.0;  // after 1 s of lowering at rest
  double radius = kRigRadius, width = kRigWidth;  // the wheel's [m]
  double wheel_mass = 10.0;  // [kg]; its carrier takes the rest of the load
};

struct RigRun {
  double sinkage[2] = {0, 0};  // per wheel, mean over the last second [m]
  double pull = 0;             // the wheels' drawbar pull together (minus the rail's force) [N]
  double sim_seconds = 0;
};

RigRun RunRig(const Context& context, const RigSetup& setup, std::string* not_applicable);

}  // namespace simpartner::validate
