// The cameras a SIM_MODEL announces (sensor_t.KIND_CAMERA), checked, and
// the maths of one: where it looks from on its body, its pinhole
// projection, which steps it renders, and its depth in metres or
// millimetres. No GL here, so all of it is unit tested on plain messages.
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

#include "simpartner/model_t.hpp"
#include "simpartner/viewer/camera.h"

namespace simpartner::camera {

// sensor_t.params[5] of a camera, and the image_t.FORMAT_* of its depth.
enum class DepthFormat { kNone = 0, kMetres = 1, kMillimetres = 2 };

struct CameraSensor {
  int index = 0;        // into model_t.sensors
  std::string name;
  std::string robot;    // its robot's name ("" for none)
  int body = 0;         // into model_t.bodies
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // camera frame in the body frame
  double rate = 0;      // [Hz of sim time]
  int width = 0;        // [pixels]
  int height = 0;
  double fov = 0;       // [rad] horizontal
  double near = 0;      // [m]
  double far = 0;       // [m]
  DepthFormat depth = DepthFormat::kNone;
  int64_t period_steps = 1;  // renders the first state of every period of this many steps
};

// The cameras of `model` in sensor order. One whose announcement does not
// fit (parameter count, ranges, body index, mount) is left out, and why
// goes to *problems: "SIM_MODEL: sensors[4] (camera 'Eye'): params[2]
// (fov) = 4 rad is out of range (0, pi)".
std::vector<CameraSensor> CamerasOfModel(const model_t& model, std::vector<std::string>* problems);

// Focal length in pixels: (width / 2) / tan(fov / 2).
double FocalPixels(const CameraSensor& camera);

// The camera's view of the world when its body is at `body_pose`: the
// camera frame (z out, x right, y down) turned into OpenGL's eye frame,
// with a projection whose pixel (u, v) matches the pinhole of
// docs/sensors-camera.md.
viewer::Viewpoint CameraViewpoint(const CameraSensor& camera, const Eigen::Isometry3d& body_pose);

// The frames a camera owes: the first state of each period of
// period_steps steps (step / period_steps changed) starts one. Steps that
// go back (a reset) start over.
class FrameSchedule {
 public:
  explicit FrameSchedule(int64_t period_steps) : period_(period_steps) {}
  // Whether the state of `step` is to be rendered; counts the frames due
  // since the last one rendered (states the bus lost still fall due).
  bool Due(int64_t step);
  int64_t due() const { return due_; }

 private:
  int64_t period_;
  int64_t last_frame_ = -1;
  int64_t due_ = 0;
};

// A depth buffer value (0 at near, 1 at far) as metres along the optical
// axis; +inf where nothing was drawn (1).
float DepthMetres(float buffer_depth, double near, double far);
// Metres as image_t.FORMAT_DEPTH_U16 holds them: rounded millimetres, 0 for
// nothing (+inf) or beyond 65.535 m.
uint16_t DepthMillimetres(float metres);
// A depth buffer (rows top to bottom) as the bytes of an image_t of the
// camera's depth format (little-endian float32 metres or uint16 mm).
std::vector<uint8_t> DepthBytes(const std::vector<float>& buffer_depth, const CameraSensor& camera);

}  // namespace simpartner::camera
