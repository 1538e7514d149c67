// The viewer's camera: an orbit about a target point (yaw about the world's
// up axis, pitch above the horizontal, distance), with pan, zoom and free
// flight of the target. The same matrices drive OpenGL and Project(), so a
// test can tell which pixel shows a given world point.
#pragma once

#include <Eigen/Geometry>

#include <optional>

namespace simpartner::viewer {

// What the renderer needs of a point of view: the viewer's orbit camera
// and a camera sensor on a body (simpartner-camera) both make one.
struct Viewpoint {
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();        // world to eye, column-major
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();  // eye to clip, column-major
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();
  Eigen::Vector3d looked_at = Eigen::Vector3d::UnitX();  // centre of the ground drawn around it
  double distance = 1.0;  // [m] eye to looked_at: the ground reaches 20 times as far
};

struct Camera {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double yaw = 0.0;        // [rad] about up; 0: the eye is on the +forward side of the target
  double pitch = 0.35;     // [rad] eye above the target's horizontal plane, (-pi/2, pi/2)
  double distance = 5.0;   // [m] eye to target
  double fov_y = 0.7854;   // [rad] vertical field of view (45 deg)
  double near_clip = 0.05; // [m]
  double far_clip = 2000;  // [m]
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();

  // Horizontal axes: forward (world x made perpendicular to up, or z when
  // up is along x) and left = up x forward. For the y-up worlds forward is
  // +x and left is -z, so yaw 0 looks at a robot's front.
  Eigen::Vector3d Forward() const;
  Eigen::Vector3d Left() const;
  // Unit vector from the target to the eye.
  Eigen::Vector3d EyeDirection() const;
  Eigen::Vector3d Eye() const;

  // Column-major 4x4 matrices as glLoadMatrixd takes them.
  Eigen::Matrix4d View() const;
  Eigen::Matrix4d Projection(double aspect) const;
  Viewpoint ToViewpoint(double aspect) const;

  // Pixel (x right, y down from the top-left corner, pixel centres at +0.5)
  // where world point p appears in a width x height image; nullopt when p
  // is behind the eye or outside the clip range.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& p, int width, int height) const;

  // Mouse and key motions.
  void Orbit(double dyaw, double dpitch);
  // Moves the target in the view plane by a drag of (dx, dy) pixels, so the
  // point under the cursor follows it.
  void Pan(double dx_pixels, double dy_pixels, int height);
  // factor < 1 moves in.
  void Zoom(double factor);
  // Free flight: moves the target (and with it the eye) along the
  // horizontal view direction, to the left and along up [m].
  void Fly(double forward, double left, double rise);
};

// A camera that frames a sphere (centre, radius) from the front-left of a
// robot facing forward, slightly from above.
Camera FramingCamera(const Eigen::Vector3d& up, const Eigen::Vector3d& centre, double radius);

}  // namespace simpartner::viewer
