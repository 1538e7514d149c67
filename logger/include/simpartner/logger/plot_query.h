// simpartner-query plot: one logged simulation's positions, velocities,
// joint angles, rates and forces, wheel loads or track as a gnuplot plot
// (simpartner/plot.h draws it).
#pragma once

#include <limits>
#include <string>

#include "simpartner/logger/db.h"
#include "simpartner/plot.h"

namespace simpartner::logger {

enum class PlotKind {
  kPosition,     // a body's x, y, z against time
  kVelocity,     // a body's vx, vy, vz against time (central differences)
  kAngle,        // a joint's angle (continuous) against time
  kRate,         // a joint's rate
  kForce,        // a joint's constraint force on body1 (components and magnitude)
  kWheelForces,  // the contact force along "up" (against gravity) of every wheel, a panel each
  kTrack,        // a body's track seen from above (equal axes, at least kTrackMinExtent)
};

// The smallest span of either axis of a track [m]: a robot that stands
// still shows as a dot in a metre, not its jitter blown up.
inline constexpr double kTrackMinExtent = 1.0;

// "position", "velocity", "angle", "rate", "force", "wheel-forces", "track";
// throws Error naming the word and the kinds (with a did-you-mean).
PlotKind ParsePlotKind(const std::string& word);

struct PlotRequest {
  PlotKind kind = PlotKind::kPosition;
  std::string simulation = "last";
  std::string name;  // the body or joint; wheel-forces: "" = every body named Wheel*
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
};

// The plot's series from the database (title names the simulation).
// Throws Error for an unknown simulation, body or joint (with a
// did-you-mean), a missing name, an empty time range or no steps in it;
// DbError for the database.
Plot MakePlot(DbConnection* db, const PlotRequest& request);

}  // namespace simpartner::logger
