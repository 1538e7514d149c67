#include "simpartner/viewer/camera.h"

#include <algorithm>
#include <cmath>

namespace simpartner::viewer {
namespace {
constexpr double kMaxPitch = 1.55;  // just short of straight up/down, where yaw has no meaning
constexpr double kMinDistance = 0.05;
constexpr double kMaxDistance = 1000.0;
}  // namespace

Eigen::Vector3d Camera::Forward() const {
  const Eigen::Vector3d u = up.normalized();
  const Eigen::Vector3d reference =
      std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  return (reference - reference.dot(u) * u).normalized();
}

Eigen::Vector3d Camera::Left() const { return up.normalized().cross(Forward()); }

Eigen::Vector3d Camera::EyeDirection() const {
  return std::cos(pitch) * (std::cos(yaw) * Forward() + std::sin(yaw) * Left()) +
         std::sin(pitch) * up.normalized();
}

Eigen::Vector3d Camera::Eye() const { return target + distance * EyeDirection(); }

Eigen::Matrix4d Camera::View() const {
  // gluLookAt: camera z points from the target to the eye.
  const Eigen::Vector3d z = EyeDirection();
  const Eigen::Vector3d x = up.normalized().cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  const Eigen::Vector3d eye = Eye();
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.block<1, 3>(0, 0) = x.transpose();
  view.block<1, 3>(1, 0) = y.transpose();
  view.block<1, 3>(2, 0) = z.transpose();
  view(0, 3) = -x.dot(eye);
  view(1, 3) = -y.dot(eye);
  view(2, 3) = -z.dot(eye);
  return view;
}

Eigen::Matrix4d Camera::Projection(double aspect) const {
  // gluPerspective.
  const double f = 1.0 / std::tan(fov_y / 2);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = f / aspect;
  p(1, 1) = f;
  p(2, 2) = (far_clip + near_clip) / (near_clip - far_clip);
  p(2, 3) = 2 * far_clip * near_clip / (near_clip - far_clip);
  p(3, 2) = -1;
  return p;
}

Viewpoint Camera::ToViewpoint(double aspect) const {
  Viewpoint v;
  v.view = View();
  v.projection = Projection(aspect);
  v.eye = Eye();
  v.looked_at = target;
  v.distance = distance;
  return v;
}

std::optional<Eigen::Vector2d> Camera::Project(const Eigen::Vector3d& p, int width,
                                               int height) const {
  const Eigen::Vector4d clip =
      Projection(static_cast<double>(width) / height) * View() * p.homogeneous();
  if (clip.w() <= 0) return std::nullopt;
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  if (ndc.z() < -1 || ndc.z() > 1) return std::nullopt;
  return Eigen::Vector2d((ndc.x() + 1) / 2 * width, (1 - ndc.y()) / 2 * height);
}

void Camera::Orbit(double dyaw, double dpitch) {
  yaw = std::remainder(yaw + dyaw, 2 * M_PI);
  pitch = std::clamp(pitch + dpitch, -kMaxPitch, kMaxPitch);
}

void Camera::Pan(double dx_pixels, double dy_pixels, int height) {
  // One pixel at the target's distance spans this many metres.
  const double metres_per_pixel = 2 * distance * std::tan(fov_y / 2) / std::max(height, 1);
  const Eigen::Vector3d z = EyeDirection();
  const Eigen::Vector3d x = up.normalized().cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  target += (-dx_pixels * x + dy_pixels * y) * metres_per_pixel;
}

void Camera::Zoom(double factor) {
  distance = std::clamp(distance * factor, kMinDistance, kMaxDistance);
}

void Camera::Fly(double forward, double left, double rise) {
  // Horizontal heading of the view (from the eye towards the target).
  const Eigen::Vector3d heading = -(std::cos(yaw) * Forward() + std::sin(yaw) * Left());
  const Eigen::Vector3d heading_left = up.normalized().cross(heading);
  target += forward * heading + left * heading_left + rise * up.normalized();
}

Camera FramingCamera(const Eigen::Vector3d& up, const Eigen::Vector3d& centre, double radius) {
  Camera camera;
  camera.up = up.normalized();
  camera.target = centre;
  camera.yaw = 35.0 * M_PI / 180;
  // From above enough to look over the 2 m walls of the maze world.
  camera.pitch = 32.0 * M_PI / 180;
  // The sphere fills most of the view height.
  camera.distance =
      std::clamp(1.25 * std::max(radius, 0.1) / std::sin(camera.fov_y / 2), 1.0, kMaxDistance);
  return camera;
}

}  // namespace simpartner::viewer
