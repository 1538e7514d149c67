#include "simpartner/sim/soil_mechanics.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace simpartner::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Below these a wheel neither spins nor moves: no shear displacement.
constexpr double kStillSpin = 1e-6;   // [rad/s]
constexpr double kStillSpeed = 1e-6;  // [m/s]
// A wheel dragged without turning: every rim point has slid far; the
// shear displacement is taken as this many K (1 - e^-40 of the strength).
constexpr double kSlidFar = 40.0;

// The wheel's own frame: its plane's up (the surface's up, less any
// component along the axle) and forward.
struct WheelFrame {
  Eigen::Vector3d up, forward;
  bool valid = false;
};

WheelFrame FrameOf(const WheelState& wheel, const SoilSurface& surface) {
  WheelFrame frame;
  const Eigen::Vector3d in_plane =
      surface.up - surface.up.dot(wheel.axle) * wheel.axle;
  if (in_plane.norm() < 1e-6) return frame;  // axle upright: not rolling on the soil
  frame.up = in_plane.normalized();
  frame.forward = frame.up.cross(wheel.axle).normalized();
  frame.valid = true;
  return frame;
}

double HeightAbove(const SoilSurface& surface, const Eigen::Vector3d& point) {
  return (point - surface.origin).dot(surface.up);
}

Eigen::Vector2d GroundCoordinates(const SoilSurface& surface, const Eigen::Vector3d& point) {
  const Eigen::Vector3d d = point - surface.origin;
  return {d.dot(surface.u_axis), d.dot(surface.up.cross(surface.u_axis))};
}

// The rim point at theta.
Eigen::Vector3d RimPoint(const WheelState& wheel, const WheelFrame& frame, double theta) {
  return wheel.centre + wheel.radius * (-std::cos(theta) * frame.up + std::sin(theta) * frame.forward);
}

// The arc of the rim below the untouched surface: [-theta_max, theta_max].
double ArcHalfAngle(double sinkage, double radius, bool* stuck) {
  const double depth = std::min(sinkage, radius);
  *stuck = sinkage >= radius;
  return std::acos(1.0 - depth / radius);
}

// Wong and Reece's shear displacement of the rim point at theta, which
// entered the soil at theta_front.
double ShearDisplacement(const Soil& soil, double radius, double v, double omega,
                         double theta_front, double theta) {
  if (std::abs(omega) > kStillSpin)
    return radius * (theta_front - theta) - (v / omega) * (std::sin(theta_front) - std::sin(theta));
  if (std::abs(v) > kStillSpeed) return -std::copysign(kSlidFar * soil.shear_modulus, v);
  return 0.0;
}

double Slip(double radius, double v, double omega) {
  const double rim = radius * omega;
  if (std::abs(rim) >= std::abs(v) && std::abs(rim) > kStillSpeed) return 1.0 - v / rim;
  if (std::abs(v) > kStillSpeed) return rim / v - 1.0;
  return 0.0;
}

}  // namespace

Soil Soil::From(const model::SoilParameters& p) {
  Soil soil;
  soil.n = p.n;
  soil.k_c = p.k_c * 1e3;      // kN/m^(n+1) -> N/m^(n+1)
  soil.k_phi = p.k_phi * 1e3;  // kN/m^(n+2) -> N/m^(n+2)
  soil.cohesion = p.cohesion * 1e3;
  soil.tan_phi = std::tan(p.friction_angle * kPi / 180.0);
  soil.shear_modulus = p.shear_modulus;
  soil.unloading_stiffness = p.unloading_stiffness * 1e3;
  soil.viscosity = p.viscosity * 1e3;
  return soil;
}

double Soil::Pressure(double z, double b) const {
  return z > 0.0 ? (k_c / b + k_phi) * std::pow(z, n) : 0.0;
}

double Soil::Shear(double sigma, double j) const {
  const double strength = cohesion + sigma * tan_phi;
  return std::copysign(strength * (1.0 - std::exp(-std::abs(j) / shear_modulus)), j);
}

SoilMemory::SoilMemory(double cell_size) : cell_size_(cell_size) {}

uint64_t SoilMemory::Key(double u, double w) const {
  // Two's complement cell indices, 32 bits each (shifting a negative
  // signed value is undefined).
  const auto iu = static_cast<uint64_t>(static_cast<int64_t>(std::floor(u / cell_size_)));
  const auto iw = static_cast<uint64_t>(static_cast<int64_t>(std::floor(w / cell_size_)));
  return (iu << 32) ^ (iw & 0xffffffffULL);
}

double SoilMemory::Deepest(double u, double w) const {
  const auto it = deepest_.find(Key(u, w));
  return it == deepest_.end() ? 0.0 : it->second;
}

void SoilMemory::Press(double u, double w, double z) {
  if (z <= 0.0) return;
  double& deepest = deepest_[Key(u, w)];
  deepest = std::max(deepest, z);
}

double PressureWithMemory(const Soil& soil, double z, double z_max, double b) {
  if (z >= z_max) return soil.Pressure(z, b);
  return std::max(0.0, soil.Pressure(z_max, b) - soil.unloading_stiffness * (z_max - z));
}

WheelSoilForces WheelOnSoil(const Soil& soil, const WheelState& wheel, const SoilSurface& surface,
                            const SoilMemory& memory, int samples) {
  WheelSoilForces out;
  const WheelFrame frame = FrameOf(wheel, surface);
  if (!frame.valid) return out;
  const double r = wheel.radius, b = wheel.width;
  out.sinkage = -HeightAbove(surface, wheel.centre - r * frame.up);
  if (out.sinkage <= 0.0) return out;
  const double half = ArcHalfAngle(out.sinkage, r, &out.stuck);
  out.forward_speed = wheel.velocity.dot(frame.forward);
  out.spin = -wheel.angular_velocity.dot(wheel.axle);
  out.slip = Slip(r, out.forward_speed, out.spin);

  // Normal stresses first: where the arc is loaded decides theta_front.
  const double step = 2.0 * half / samples;
  std::vector<double> theta(static_cast<size_t>(samples)), sigma(static_cast<size_t>(samples));
  out.theta_front = -half;
  out.theta_rear = half;
  for (int k = 0; k < samples; ++k) {
    const double t = -half + (k + 0.5) * step;
    const Eigen::Vector3d point = RimPoint(wheel, frame, t);
    const double z = -HeightAbove(surface, point);
    const Eigen::Vector2d at = GroundCoordinates(surface, point);
    const double z_max = memory.Deepest(at.x(), at.y());
    double s = PressureWithMemory(soil, z, z_max, b);
    const double sinking = -(wheel.velocity + wheel.angular_velocity.cross(point - wheel.centre))
                                .dot(surface.up);
    // The soil's damping: on any loaded point, sinking or rising.
    if (s > 0.0) s = std::max(0.0, s + soil.viscosity * sinking);
    theta[static_cast<size_t>(k)] = t;
    sigma[static_cast<size_t>(k)] = s;
    if (s > 0.0) {
      out.theta_front = std::max(out.theta_front, t + 0.5 * step);
      out.theta_rear = std::min(out.theta_rear, t - 0.5 * step);
    }
  }
  const double area = b * r * step;
  for (int k = 0; k < samples; ++k) {
    const double s = sigma[static_cast<size_t>(k)], t = theta[static_cast<size_t>(k)];
    if (s <= 0.0) continue;
    const Eigen::Vector3d inward = std::cos(t) * frame.up - std::sin(t) * frame.forward;
    const Eigen::Vector3d tangent = std::cos(t) * frame.forward + std::sin(t) * frame.up;
    const double j = ShearDisplacement(soil, r, out.forward_speed, out.spin, out.theta_front, t);
    const double tau = soil.Shear(s, j);
    out.normal_force += s * area * inward;
    out.shear_force += tau * area * tangent;
    out.shear_torque += r * tau * area;
    out.shear_strength += (soil.cohesion + s * soil.tan_phi) * area;
    out.contact_area += area;
  }
  out.touching = out.contact_area > 0.0;
  return out;
}

void PressWheel(const WheelState& wheel, const SoilSurface& surface, SoilMemory* memory,
                int samples) {
  const WheelFrame frame = FrameOf(wheel, surface);
  if (!frame.valid) return;
  const double sinkage = -HeightAbove(surface, wheel.centre - wheel.radius * frame.up);
  if (sinkage <= 0.0) return;
  bool stuck = false;
  const double half = ArcHalfAngle(sinkage, wheel.radius, &stuck);
  const double step = 2.0 * half / samples;
  for (int k = 0; k < samples; ++k) {
    const Eigen::Vector3d point = RimPoint(wheel, frame, -half + (k + 0.5) * step);
    const Eigen::Vector2d at = GroundCoordinates(surface, point);
    memory->Press(at.x(), at.y(), -HeightAbove(surface, point));
  }
}

}  // namespace simpartner::sim
