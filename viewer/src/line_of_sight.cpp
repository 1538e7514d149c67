#include "simpartner/viewer/line_of_sight.h"

#include <algorithm>

#include "simpartner/line_entry.h"

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
      const auto span = LineThroughSphere(from, direction, pose.translation(), body.geometry.size[0]);
      if (span) hit = span->RayHit();
    } else if (const auto half = BoxHalfExtents(body.geometry)) {
      const Eigen::Matrix3d to_body = pose.linear().transpose();
      const auto span = LineThroughBox(to_body * (from - pose.translation()), to_body * direction, *half);
      if (span) hit = span->RayHit();
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
