#include "soil_contact.h"

#include <algorithm>
#include <cmath>

namespace simpartner::sim {
namespace {

// Points along the loaded arc (soil_mechanics.h).
constexpr int kArcSamples = 64;

// A unit vector along the surface: the memory's first coordinate.
Eigen::Vector3d AlongSurface(const Eigen::Vector3d& up) {
  const Eigen::Vector3d seed =
      std::abs(up.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  return (seed - seed.dot(up) * up).normalized();
}

// Drops the entries of `wheels` no contact saw this step (a wheel that
// left the soil) and marks the rest unseen for the next.
template <class Map>
void ForgetUnseen(Map* wheels) {
  for (auto it = wheels->begin(); it != wheels->end();) {
    if (!it->second.seen) {
      it = wheels->erase(it);
    } else {
      it->second.seen = false;
      ++it;
    }
  }
}

}  // namespace

int SoilContacts::AddPlane(const Eigen::Vector4d& plane, const model::SoilParameters& soil) {
  const double length = plane.head<3>().norm();
  Ground ground{Soil::From(soil), SoilMemory{}, SoilSurface{}};
  ground.surface.up = plane.head<3>() / length;
  ground.surface.origin = ground.surface.up * (plane[3] / length);
  ground.surface.u_axis = AlongSurface(ground.surface.up);
  grounds_.push_back(std::move(ground));
  return grounds() - 1;
}

int SoilContacts::AddHeightfield(const model::SoilParameters& soil,
                                 const model::Heightfield& shape, const Eigen::Isometry3d& pose) {
  grounds_.push_back(Ground{Soil::From(soil), SoilMemory{}, SoilSurface{}, &shape, pose});
  return grounds() - 1;
}

namespace {

// The field's normal at (x, z) of its own frame (y up): slopes of the
// interpolated surface by differences over a quarter cell each way,
// inside the field (its heights are clamped at the border).
Eigen::Vector3d FieldNormal(const model::Heightfield& h, double x, double z) {
  auto slope = [](double at, double cell, double half_extent, const auto& height) {
    const double lo = std::clamp(at - 0.25 * cell, -half_extent, half_extent);
    const double hi = std::clamp(at + 0.25 * cell, -half_extent, half_extent);
    return hi > lo ? (height(hi) - height(lo)) / (hi - lo) : 0.0;
  };
  const double dx = h.width / std::max(1, h.columns - 1), dz = h.depth / std::max(1, h.rows - 1);
  const double slope_x = slope(x, dx, 0.5 * h.width, [&](double u) { return h.HeightAt(u, z); });
  const double slope_z = slope(z, dz, 0.5 * h.depth, [&](double w) { return h.HeightAt(x, w); });
  return Eigen::Vector3d(-slope_x, 1.0, -slope_z).normalized();
}

}  // namespace

SoilSurface SoilContacts::FieldPlane(const Ground& ground, double x, double z) {
  const model::Heightfield& h = *ground.shape;
  SoilSurface surface;
  surface.origin = ground.pose * Eigen::Vector3d(x, h.HeightAt(x, z), z);
  surface.up = ground.pose.linear() * FieldNormal(h, x, z);
  surface.u_axis = AlongSurface(surface.up);
  surface.keyed_apart = true;
  surface.key_origin = ground.pose.translation();
  surface.key_u = ground.pose.linear() * Eigen::Vector3d::UnitX();
  surface.key_w = ground.pose.linear() * Eigen::Vector3d::UnitZ();
  return surface;
}

SoilSurface SoilContacts::SurfaceUnder(const Ground& ground, const WheelState& wheel) {
  if (ground.shape == nullptr) return ground.surface;
  // In the field's frame (y up): the lowest rim point for the field's up,
  // then again for the normal found there.
  const Eigen::Isometry3d to_field = ground.pose.inverse();
  const Eigen::Vector3d centre = to_field * wheel.centre;
  const Eigen::Vector3d axle = to_field.linear() * wheel.axle;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY(), lowest = centre;
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::Vector3d in_plane = up - up.dot(axle) * axle;
    if (in_plane.norm() < 1e-6) break;  // axle upright: no lowest point
    lowest = centre - wheel.radius * in_plane.normalized();
    up = FieldNormal(*ground.shape, lowest.x(), lowest.z());
  }
  return FieldPlane(ground, lowest.x(), lowest.z());
}

SoilSurface SoilContacts::SurfaceBelow(const Ground& ground, const Eigen::Vector3d& point) {
  if (ground.shape == nullptr) return ground.surface;
  const Eigen::Vector3d at = ground.pose.inverse() * point;
  return FieldPlane(ground, at.x(), at.z());
}

std::optional<SoilContactRows> SoilContacts::Contact(int index, int body,
                                                     const WheelState& wheel) {
  Ground& ground = grounds_.at(static_cast<size_t>(index));
  const SoilSurface surface = SurfaceUnder(ground, wheel);
  WheelSoilSlopes slopes;
  // The soil keeps this state's rut as it answers it.
  const WheelSoilForces now =
      PressWheelOnSoil(ground.soil, wheel, surface, &ground.memory, kArcSamples, &slopes);
  if (!now.touching) return std::nullopt;

  SoilContactRows rows;
  rows.up = surface.up;
  const Eigen::Vector3d wheel_up = (rows.up - rows.up.dot(wheel.axle) * wheel.axle).normalized();
  rows.forward = wheel_up.cross(wheel.axle).normalized();
  rows.across = rows.up.cross(rows.forward);
  rows.centre = wheel.centre;
  rows.point = wheel.centre - wheel.radius * wheel_up;
  // Normal: the soil's stiffness against sinking further.
  rows.stiffness = std::max(kLeastSoilStiffness, slopes.stiffness);
  // Along forward: the shear's force against the slip velocity of the
  // lowest rim point; across: the side force against the wheel's speed
  // along it. Each slope at least kLeastShearSlope steep.
  rows.slip_velocity = now.forward_speed - wheel.radius * now.spin;
  rows.thrust = now.shear_force.dot(rows.forward);
  rows.thrust_slope = std::min(-kLeastShearSlope, slopes.thrust_slope);
  rows.side_velocity = wheel.velocity.dot(rows.across);
  rows.side_force = now.side_force * wheel.axle.dot(rows.across);
  rows.side_slope = std::min(-kLeastShearSlope, slopes.side_slope);
  rows.shear_strength = now.shear_strength;
  // Through the centre: the normal stresses and the shear's part along up;
  // the shear's torque about the axle beyond the row's r T at the rim.
  rows.force = now.normal_force + now.shear_force.dot(rows.up) * rows.up;
  rows.torque = (now.shear_torque - wheel.radius * rows.thrust) * wheel.axle;

  WheelSoilReadout readout;
  readout.body = body;
  readout.ground = ground.shape != nullptr ? SoilGround::kHeightfield : SoilGround::kPlane;
  readout.sinkage = now.sinkage;
  readout.normal_force = now.normal_force;
  readout.forward = rows.forward;
  readout.axle = wheel.axle;
  readout.lowest_point = rows.point;
  readout.width = wheel.width;
  readout.surface_origin = surface.origin;
  readout.up = surface.up;
  readout.surface_u_axis = surface.u_axis;
  WheelHistory& history = history_[{index, body}];
  history.seen = true;
  // Held by its anchor the wheel is at rest: its slip, a ratio of speeds
  // below 1 mm/s, would be noise (+-0.1 on sand), and is 0.
  const bool held = HoldAtRest(index, body, wheel, now.normal_force, &history, &rows);
  readout.slip = held ? 0.0 : now.slip;
  readout.stuck = SlippingLong(readout.slip, &history) || now.stuck;
  // The plain part of what the step applies; RowForce adds the rows'.
  readout.shear_force = rows.force - now.normal_force;
  readout.axle_torque = rows.torque.dot(wheel.axle);
  rows.readout = static_cast<int>(pressing_.size());
  pressing_.push_back(readout);
  return rows;
}

void SoilContacts::RowForce(const SoilContactRows& rows, const Eigen::Vector3d& force) {
  if (rows.readout < 0) return;
  WheelSoilReadout& readout = pressing_.at(static_cast<size_t>(rows.readout));
  const Eigen::Vector3d normal = force.dot(rows.up) * rows.up;
  readout.normal_force += normal;
  readout.shear_force += force - normal;
  // The rows act at the lowest rim point: r T along the axle for a thrust
  // T, the share rows.torque left out of the shear's torque.
  readout.axle_torque += (rows.point - rows.centre).cross(force).dot(readout.axle);
}

bool SoilContacts::HoldAtRest(int ground, int body, const WheelState& wheel,
                              const Eigen::Vector3d& normal_force, WheelHistory* history,
                              SoilContactRows* rows) {
  const double K = grounds_.at(static_cast<size_t>(ground)).soil.shear_modulus;
  const Eigen::Vector3d rim_velocity =
      wheel.velocity + wheel.angular_velocity.cross(rows->point - wheel.centre);
  const auto key = std::make_pair(ground, body);
  if (!history->has_velocity) {  // its first step on soil: the mean is this one
    history->velocity = wheel.velocity;
    history->rim_velocity = rim_velocity;
    history->has_velocity = true;
  }
  const bool still = (wheel.velocity + history->velocity).norm() < 2 * kRestSpeed &&
                     (rim_velocity + history->rim_velocity).norm() < 2 * kRestSpeed;
  history->velocity = wheel.velocity;
  history->rim_velocity = rim_velocity;
  auto it = anchors_.find(key);
  if (!still && it == anchors_.end()) return false;
  if (it == anchors_.end()) it = anchors_.emplace(key, Anchor{rows->point, false}).first;
  const Eigen::Vector3d j = rows->point - it->second.at;
  if (j.norm() > K || !still) {  // slid past the elastic range, or moving: the slip law
    anchors_.erase(it);
    return false;
  }
  it->second.seen = true;
  // The anchor is the shear at rest: the slip law's shear (its part along
  // up, its torque beyond the row) has no place beside it. Left in, it
  // would follow the slip ratio of a wheel barely moving, which is noise.
  rows->force = normal_force;
  rows->torque.setZero();
  // Each row: the spring strength / K of the displacement at the end of
  // the step, j + h v+, and a damper of strength / kRestSpeed.
  const double spring = rows->shear_strength / K;
  const double slope =
      std::min(-kLeastShearSlope, -(spring * stepsize_ + rows->shear_strength / kRestSpeed));
  rows->slip_velocity = rim_velocity.dot(rows->forward);
  rows->thrust = -spring * j.dot(rows->forward) + slope * rows->slip_velocity;
  rows->thrust_slope = slope;
  rows->side_velocity = rim_velocity.dot(rows->across);
  rows->side_force = -spring * j.dot(rows->across) + slope * rows->side_velocity;
  rows->side_slope = slope;
  return true;
}

bool SoilContacts::SlippingLong(double slip, WheelHistory* history) const {
  history->slipping_seconds = slip >= kStuckSlip ? history->slipping_seconds + stepsize_ : 0.0;
  return history->slipping_seconds >= kStuckSeconds;
}

std::optional<SoilContactRows> SoilContacts::PlateContact(int index, const PlateState& plate) {
  Ground& ground = grounds_.at(static_cast<size_t>(index));
  const SoilSurface surface = SurfaceBelow(ground, plate.pose.translation());
  const PlateSoilForces now = PressPlateOnSoil(ground.soil, plate, surface, &ground.memory);
  if (!now.touching) return std::nullopt;
  SoilContactRows rows;
  rows.up = surface.up;
  rows.forward = surface.u_axis;
  rows.across = rows.up.cross(rows.forward);
  rows.centre = rows.point = now.centroid;
  rows.force = now.normal_force * rows.up;
  rows.stiffness = std::max(kLeastSoilStiffness, now.stiffness);
  rows.shear_strength = now.shear_strength;
  // Held by the shear: a creep law through 0, f = -(strength / creep) v.
  const Eigen::Vector3d v =
      plate.velocity + plate.angular_velocity.cross(now.centroid - plate.pose.translation());
  const double slope = -std::max(kLeastShearSlope, now.shear_strength / kPlateCreepSpeed);
  rows.slip_velocity = v.dot(rows.forward);
  rows.thrust = slope * rows.slip_velocity;
  rows.thrust_slope = slope;
  rows.side_velocity = v.dot(rows.across);
  rows.side_force = slope * rows.side_velocity;
  rows.side_slope = slope;
  return rows;
}

void SoilContacts::AfterStep(std::vector<std::string>* messages) {
  for (size_t g = 0; g < grounds_.size(); ++g)
    if (const size_t forgotten = grounds_[g].memory.ForgetOldest(kMaxSoilCells))
      messages->push_back("soil: the ruts of soil ground " + std::to_string(g) + " filled " +
                          std::to_string(kMaxSoilCells) + " cells of its memory; the " +
                          std::to_string(forgotten) +
                          " pressed longest ago are forgotten (a wheel on them meets untouched "
                          "soil)");
  last_step_.swap(pressing_);
  pressing_.clear();
  ForgetUnseen(&history_);
  ForgetUnseen(&anchors_);
}

}  // namespace simpartner::sim
