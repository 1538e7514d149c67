#include "soil_plate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "simpartner/line_entry.h"

namespace simpartner::sim {
namespace {

constexpr double kParallel = 1e-12;

// Where the line p + t d (d unit) enters the sphere of radius r about c.
std::optional<double> SphereEntry(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                  const Eigen::Vector3d& c, double r) {
  const std::optional<LineSpan> span = LineThroughSphere(p, d, c, r);
  if (!span) return std::nullopt;
  return span->enter;
}

// A capsule of radius r about the segment z in [-half, half].
std::optional<double> CapsuleEntry(const Eigen::Vector3d& p, const Eigen::Vector3d& d, double r,
                                   double half) {
  std::optional<double> best;
  auto take = [&best](std::optional<double> t) {
    if (t && (!best || *t < *best)) best = t;
  };
  take(SphereEntry(p, d, Eigen::Vector3d(0, 0, half), r));
  take(SphereEntry(p, d, Eigen::Vector3d(0, 0, -half), r));
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a > kParallel) {
    const double b = p.x() * d.x() + p.y() * d.y();
    const double c = p.x() * p.x() + p.y() * p.y() - r * r;
    const double disc = b * b - a * c;
    if (disc >= 0.0) {
      const double t = (-b - std::sqrt(disc)) / a;
      if (std::abs(p.z() + t * d.z()) <= half) take(t);
    }
  }
  return best;
}

// Where the line p + t d (the body's own frame) enters the body.
std::optional<double> EntryInBodyFrame(const PlateState& plate, const Eigen::Vector3d& p,
                                       const Eigen::Vector3d& d) {
  switch (plate.kind) {
    case model::GeometryKind::kBox: {
      const std::optional<LineSpan> span = LineThroughBox(p, d, 0.5 * plate.size);
      return span ? std::optional<double>(span->enter) : std::nullopt;
    }
    case model::GeometryKind::kSphere:
      return SphereEntry(p, d, Eigen::Vector3d::Zero(), plate.size.x());
    case model::GeometryKind::kCapsule:
      return CapsuleEntry(p, d, plate.size.x(), 0.5 * plate.size.y());
    default: return std::nullopt;
  }
}

// The half extents of the shape's own bounding box.
Eigen::Vector3d HalfExtents(const PlateState& plate) {
  switch (plate.kind) {
    case model::GeometryKind::kBox: return 0.5 * plate.size;
    case model::GeometryKind::kSphere: return Eigen::Vector3d::Constant(plate.size.x());
    case model::GeometryKind::kCapsule:
      return Eigen::Vector3d(plate.size.x(), plate.size.x(), 0.5 * plate.size.y() + plate.size.x());
    default: return Eigen::Vector3d::Zero();
  }
}

// A rectangle of the surface's plane, in its (u, w) from its origin.
struct Rectangle {
  double u0 = 0, u1 = 0, w0 = 0, w1 = 0;
};

// One point of the footprint.
struct PlatePoint {
  Eigen::Vector3d underside;  // the body's lowest point above (below) it
  Eigen::Vector2d key;        // the memory's coordinates
  double z = 0.0;             // sinkage [m]
};

// The points of `grid` x `grid` over `area` where the body reaches below
// the surface.
int Footprint(const PlateState& plate, const SoilSurface& surface, const Rectangle& area,
              int grid, std::array<PlatePoint, kPlateFine * kPlateFine>* points) {
  const Eigen::Vector3d w_axis = surface.up.cross(surface.u_axis);
  const double du = (area.u1 - area.u0) / grid, dw = (area.w1 - area.w0) / grid;
  // Every line in the body's frame, which is found once (PlateEntry
  // inverted the pose at each point: a tenth of a step on snow).
  const Eigen::Isometry3d to_body = plate.pose.inverse();
  const Eigen::Vector3d d = to_body.linear() * surface.up;
  int count = 0;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const Eigen::Vector3d q = surface.origin + (area.u0 + (i + 0.5) * du) * surface.u_axis +
                                (area.w0 + (j + 0.5) * dw) * w_axis;
      const std::optional<double> t = EntryInBodyFrame(plate, to_body * q, d);
      if (!t || *t >= 0.0) continue;
      PlatePoint& p = (*points)[static_cast<size_t>(count++)];
      p.underside = q + *t * surface.up;
      p.key = SoilCoordinates(surface, q);
      p.z = -*t;
    }
  return count;
}

// The outline of the body seen along up, and whether any of it is below
// the surface.
bool Outline(const PlateState& plate, const SoilSurface& surface, Rectangle* out) {
  const Eigen::Vector3d half = HalfExtents(plate);
  const Eigen::Vector3d w_axis = surface.up.cross(surface.u_axis);
  double lowest = std::numeric_limits<double>::infinity();
  out->u0 = out->w0 = std::numeric_limits<double>::infinity();
  out->u1 = out->w1 = -std::numeric_limits<double>::infinity();
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d local((corner & 1 ? 1 : -1) * half.x(), (corner & 2 ? 1 : -1) * half.y(),
                                (corner & 4 ? 1 : -1) * half.z());
    const Eigen::Vector3d d = plate.pose * local - surface.origin;
    lowest = std::min(lowest, d.dot(surface.up));
    out->u0 = std::min(out->u0, d.dot(surface.u_axis));
    out->u1 = std::max(out->u1, d.dot(surface.u_axis));
    out->w0 = std::min(out->w0, d.dot(w_axis));
    out->w1 = std::max(out->w1, d.dot(w_axis));
  }
  return lowest < 0.0;
}

// The part of `outline` where the coarse grid met the body, widened by
// half a coarse cell (where the footprint's edge may lie); false when the
// coarse grid met nothing.
bool WhereItPresses(const PlateState& plate, const SoilSurface& surface, const Rectangle& outline,
                    Rectangle* out) {
  std::array<PlatePoint, kPlateFine * kPlateFine> points;
  const int count = Footprint(plate, surface, outline, kPlateCoarse, &points);
  if (count == 0) return false;
  const Eigen::Vector3d w_axis = surface.up.cross(surface.u_axis);
  const double du = 0.5 * (outline.u1 - outline.u0) / kPlateCoarse;
  const double dw = 0.5 * (outline.w1 - outline.w0) / kPlateCoarse;
  out->u0 = out->w0 = std::numeric_limits<double>::infinity();
  out->u1 = out->w1 = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d d = points[static_cast<size_t>(k)].underside - surface.origin;
    out->u0 = std::min(out->u0, d.dot(surface.u_axis) - du);
    out->u1 = std::max(out->u1, d.dot(surface.u_axis) + du);
    out->w0 = std::min(out->w0, d.dot(w_axis) - dw);
    out->w1 = std::max(out->w1, d.dot(w_axis) + dw);
  }
  out->u0 = std::max(out->u0, outline.u0);
  out->u1 = std::min(out->u1, outline.u1);
  out->w0 = std::max(out->w0, outline.w0);
  out->w1 = std::min(out->w1, outline.w1);
  return true;
}

}  // namespace

std::optional<double> PlateEntry(const PlateState& plate, const Eigen::Vector3d& point,
                                 const Eigen::Vector3d& up) {
  return EntryInBodyFrame(plate, plate.pose.inverse() * point, plate.pose.linear().transpose() * up);
}

PlateSoilForces PressPlateOnSoil(const Soil& soil, const PlateState& plate,
                                 const SoilSurface& surface, SoilMemory* memory) {
  PlateSoilForces out;
  Rectangle outline, pressing;
  if (!Outline(plate, surface, &outline) || !WhereItPresses(plate, surface, outline, &pressing))
    return out;
  std::array<PlatePoint, kPlateFine * kPlateFine> points;
  const int count = Footprint(plate, surface, pressing, kPlateFine, &points);
  if (count == 0) return out;
  const double du = (pressing.u1 - pressing.u0) / kPlateFine;
  const double dw = (pressing.w1 - pressing.w0) / kPlateFine;
  const double area = du * dw;
  // The footprint's extents: its points' cells, edge to edge.
  const Eigen::Vector3d w_axis = surface.up.cross(surface.u_axis);
  Rectangle hit{INFINITY, -INFINITY, INFINITY, -INFINITY};
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d d = points[static_cast<size_t>(k)].underside - surface.origin;
    hit.u0 = std::min(hit.u0, d.dot(surface.u_axis));
    hit.u1 = std::max(hit.u1, d.dot(surface.u_axis));
    hit.w0 = std::min(hit.w0, d.dot(w_axis));
    hit.w1 = std::max(hit.w1, d.dot(w_axis));
  }
  const double along_u = hit.u1 - hit.u0 + du, along_w = hit.w1 - hit.w0 + dw;
  out.width = std::min(along_u, along_w);
  out.length = std::max(along_u, along_w);
  const double b = out.width;
  // Each point on the memory as it was before this step (the points of
  // one cell read the same), then the memory takes them all.
  double strength = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (int k = 0; k < count; ++k) {
    const PlatePoint& p = points[static_cast<size_t>(k)];
    const PressureOnSoil pressed =
        PressureWithMemory(soil, p.z, memory->At(p.key.x(), p.key.y()), b);
    double s = pressed.pressure;
    const double ds = pressed.slope;
    const Eigen::Vector3d v =
        plate.velocity + plate.angular_velocity.cross(p.underside - plate.pose.translation());
    if (s > 0.0) s = std::max(0.0, s - soil.viscosity * v.dot(surface.up));
    out.normal_force += s * area;
    out.stiffness += ds * area;
    moment += s * area * p.underside;
    strength += (soil.cohesion + s * soil.tan_phi) * area;
    out.area += area;
    out.sinkage = std::max(out.sinkage, p.z);
  }
  for (int k = 0; k < count; ++k) {
    const PlatePoint& p = points[static_cast<size_t>(k)];
    memory->Press(p.key.x(), p.key.y(), p.z, std::pow(p.z, soil.n));
  }
  out.touching = out.area > 0.0;
  out.centroid = out.normal_force > 0.0 ? Eigen::Vector3d(moment / out.normal_force)
                                        : points[0].underside;
  // Bekker's shear of a plate of length L sliding: each point's shear
  // built up over its distance from the leading edge, averaged over L.
  const double K = soil.shear_modulus, L = std::max(out.length, 1e-6);
  out.shear_strength = strength * (1.0 - K / L * (1.0 - std::exp(-L / K)));
  return out;
}

}  // namespace simpartner::sim
