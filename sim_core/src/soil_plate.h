// A body that is not a wheel on soft soil (docs/soil.md, "Every body
// meets the soil"): a calf, a chassis, a crate. Its underside is a plate
// of whatever shape presses the soil: at each point of its footprint the
// soil pushes back with Bekker's pressure for a plate as wide as the
// footprint (b its smaller extent), on the unloading line where the soil
// was pressed deeper before (soil_mechanics.h), plus the viscosity times
// the rate the point sinks; the soil remembers what the plate pressed.
// Sliding, the soil holds it with at most Bekker's shear of a plate of
// length L, (A c + N tan phi) [1 - (K / L)(1 - exp(-L / K))]: the shear of
// each point, built up over the distance from the leading edge (Janosi
// and Hanamoto), averaged over L.
//
// The footprint is found on a grid in the surface's plane: kCoarse x
// kCoarse points over the body's outline seen from above, then kFine x
// kFine over where those met the body (a flat face: its outline exactly).
// At each point the body's underside is where the line along `up`
// through it enters the body.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>

#include "simpartner/model/model.h"
#include "simpartner/sim/soil_mechanics.h"

namespace simpartner::sim {

// A box, sphere or capsule and its motion, in world coordinates.
struct PlateState {
  model::GeometryKind kind = model::GeometryKind::kBox;
  // As model::Geometry: a box's full sides; a sphere's radius; a capsule's
  // radius and the length of its cylinder (along its z).
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the shape's frame
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // of pose's origin [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // [rad/s]
};

inline constexpr int kPlateCoarse = 12;
inline constexpr int kPlateFine = 16;

// The soil's answer to a plate, this step.
struct PlateSoilForces {
  bool touching = false;
  double sinkage = 0.0;  // the deepest point of the underside below the surface [m]
  double area = 0.0;     // of the footprint [m^2]
  double width = 0.0;    // Bekker's b: the footprint's smaller extent [m]
  double length = 0.0;   // its larger extent [m]
  double normal_force = 0.0;  // along up [N]
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // where it acts (the pressure's centroid)
  double stiffness = 0.0;       // d(normal force) / d(sinkage) [N/m]
  double shear_strength = 0.0;  // [N] the most the soil's shear holds the plate with
};

// Where the line point + t up enters `plate`: t, or none when it misses.
std::optional<double> PlateEntry(const PlateState& plate, const Eigen::Vector3d& point,
                                 const Eigen::Vector3d& up);

// The soil's answer to `plate` under `surface`, pressed before as
// `memory` says; `memory` then records what the plate presses now.
PlateSoilForces PressPlateOnSoil(const Soil& soil, const PlateState& plate,
                                 const SoilSurface& surface, SoilMemory* memory);

}  // namespace simpartner::sim
