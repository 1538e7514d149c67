#include "simpartner/viewer/line_of_sight.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace simpartner::viewer {
namespace {

// Half extents of a body's box, or of the box around its cylinder or
// capsule (axis along body z); nullopt for a point mass or a sphere.
std::optional<Eigen::Vector3d> BoxHalfExtents(const geometry_t& g) {
  switch (g.kind) {
    case geometry_t::KIND_BOX: return Eigen::Vector3d(g.size[0], g.size[1], g.size[2]) / 2;
    case geometry_t::KIND_CYLINDER: return Eigen::Vector3d(g.size[0], g.size[0], g.size[1] / 2);
    case geometry_t::KIND_CAPSULE:
      return Eigen::Vector3d(g.size[0], g.size[0], g.size[1] / 2 + g.size[0]);
    default: return std::nullopt;
  }
}

// Entry distance of a ray (in the box's frame) into an axis-aligned box
// centred at the origin (the slab method); 0 when it starts inside.
std::optional<double> RayBox(const Eigen::Vector3d& from, const Eigen::Vector3d& dir,
                             const Eigen::Vector3d& half) {
  double enter = 0.0, leave = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dir[a]) < 1e-12) {
      if (std::abs(from[a]) > half[a]) return std::nullopt;
      continue;
    }
    double t1 = (-half[a] - from[a]) / dir[a];
    double t2 = (half[a] - from[a]) / dir[a];
    if (t1 > t2) std::swap(t1, t2);
    enter = std::max(enter, t1);
    leave = std::min(leave, t2);
    if (enter > leave) return std::nullopt;
  }
  return enter;
}

std::optional<double> RaySphere(const Eigen::Vector3d& from, const Eigen::Vector3d& dir,
                                const Eigen::Vector3d& centre, double radius) {
  const Eigen::Vector3d m = from - centre;
  const double b = m.dot(dir);
  const double c = m.squaredNorm() - radius * radius;
  if (c <= 0) return 0.0;  // starts inside
  const double disc = b * b - c;
  if (b > 0 || disc < 0) return std::nullopt;
  return -b - std::sqrt(disc);
}

}  // namespace

std::optional<double> FirstWorldObjectHit(const Scene& scene, const Eigen::Vector3d& from,
                                          const Eigen::Vector3d& direction, double max_distance) {
  if (!scene.has_model()) return std::nullopt;
  std::optional<double> nearest;
  const model_t& model = scene.model();
  for (int i = 0; i < model.num_bodies; ++i) {
    const body_t& body = model.bodies[static_cast<size_t>(i)];
    if (body.robot >= 0 || !body.is_static) continue;
    const Eigen::Isometry3d pose = scene.BodyPose(i);
    std::optional<double> hit;
    if (body.geometry.kind == geometry_t::KIND_SPHERE) {
      hit = RaySphere(from, direction, pose.translation(), body.geometry.size[0]);
    } else if (const auto half = BoxHalfExtents(body.geometry)) {
      const Eigen::Matrix3d to_body = pose.linear().transpose();
      hit = RayBox(to_body * (from - pose.translation()), to_body * direction, *half);
    }
    if (hit && *hit > 0 && *hit <= max_distance && (!nearest || *hit < *nearest)) nearest = hit;
  }
  return nearest;
}

Camera UnblockedCamera(const Camera& camera, const Scene& scene) {
  const auto hit = FirstWorldObjectHit(scene, camera.target, camera.EyeDirection(), camera.distance);
  if (!hit) return camera;
  Camera drawn = camera;
  drawn.distance = std::max(kMinClearDistance, *hit - kWallClearance);
  return drawn;
}

}  // namespace simpartner::viewer
