#include "simpartner/camera/camera_sensor.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "simpartner/model/model.h"
#include "simpartner/text.h"

// image_t states little-endian depth; the bytes are copied as the host holds them.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "depth bytes assume a little-endian host");

namespace simpartner::camera {
namespace {

constexpr int kParams = 6;  // width, height, fov, near, far, depth (sensor_t.lcm)

// The first reason this camera cannot be rendered, or "". The model has
// passed CheckModel (message_checks.h) in the scene: its mount is a unit
// quaternion at a finite point and its step size is positive.
std::string CameraProblem(const model_t& model, const sensor_t& s) {
  if (s.num_params != kParams)
    return "has " + std::to_string(s.num_params) + " params, a camera has " +
           std::to_string(kParams) + " (width, height, fov, near, far, depth)";
  auto bad = [&](int k, const char* what, const std::string& range) {
    return "params[" + std::to_string(k) + "] (" + what + ") = " +
           FormatNumber(s.params[static_cast<size_t>(k)], 10) + " is out of range " + range;
  };
  const double side = model::kMaxCameraSide;
  for (int k : {0, 1}) {
    const double v = s.params[static_cast<size_t>(k)];
    if (!(v >= 1 && v <= side && v == std::floor(v)))
      return bad(k, k == 0 ? "width" : "height", "(whole pixels from 1 to 4096)");
  }
  if (!(s.params[2] > 0 && s.params[2] < M_PI)) return bad(2, "fov", "(0, pi)");
  if (!(s.params[3] >= model::kMinCameraNear && std::isfinite(s.params[3])))
    return bad(3, "near", "[" + FormatNumber(model::kMinCameraNear, 10) + ", inf)");
  if (!(s.params[4] > s.params[3] && std::isfinite(s.params[4])))
    return bad(4, "far", "(near, inf)");
  if (!(s.params[5] == 0 || s.params[5] == 1 || s.params[5] == 2))
    return bad(5, "depth", "{0, 1, 2}");
  if (s.body < 0 || s.body >= model.num_bodies)
    return "body = " + std::to_string(s.body) + " is not a body of the model";
  if (!(s.rate > 0 && std::isfinite(s.rate)))
    return "rate = " + FormatNumber(s.rate, 10) + " Hz: a camera needs a rate above 0";
  return "";
}

}  // namespace

std::vector<CameraSensor> CamerasOfModel(const model_t& model, std::vector<std::string>* problems) {
  std::vector<CameraSensor> cameras;
  for (int i = 0; i < model.num_sensors; ++i) {
    const sensor_t& s = model.sensors[static_cast<size_t>(i)];
    if (s.kind != sensor_t::KIND_CAMERA) continue;
    if (const std::string problem = CameraProblem(model, s); !problem.empty()) {
      problems->push_back("SIM_MODEL: sensors[" + std::to_string(i) + "] (camera '" + s.name +
                          "'): " + problem + "; not rendered");
      continue;
    }
    CameraSensor c;
    c.index = i;
    c.name = s.name;
    if (s.robot >= 0 && s.robot < model.num_robots)
      c.robot = model.robots[static_cast<size_t>(s.robot)].name;
    c.body = s.body;
    c.mount.linear() = Eigen::Quaterniond(s.orientation[0], s.orientation[1], s.orientation[2],
                                          s.orientation[3])
                           .normalized()
                           .toRotationMatrix();
    c.mount.translation() = Eigen::Vector3d(s.position[0], s.position[1], s.position[2]);
    c.rate = s.rate;
    c.width = static_cast<int>(s.params[0]);
    c.height = static_cast<int>(s.params[1]);
    c.fov = s.params[2];
    c.near = s.params[3];
    c.far = s.params[4];
    c.depth = static_cast<DepthFormat>(static_cast<int>(s.params[5]));
    // As the sim schedules its own sensors (sim_core/src/simulation.cpp).
    c.period_steps = std::max<int64_t>(1, std::llround(1.0 / (s.rate * model.step_size)));
    cameras.push_back(c);
  }
  return cameras;
}

double FocalPixels(const CameraSensor& camera) {
  return camera.width / 2.0 / std::tan(camera.fov / 2);
}

viewer::Viewpoint CameraViewpoint(const CameraSensor& camera, const Eigen::Isometry3d& body_pose) {
  const Eigen::Isometry3d world_from_camera = body_pose * camera.mount;
  // OpenGL's eye looks along -z with y up: the camera frame's y and z flipped.
  const Eigen::Matrix4d eye_from_camera = Eigen::Vector4d(1, -1, -1, 1).asDiagonal();
  // The viewer's gluPerspective, given the vertical field of view that
  // goes with the horizontal one and the image's aspect.
  viewer::Camera lens;
  lens.fov_y = 2 * std::atan(std::tan(camera.fov / 2) * camera.height / camera.width);
  lens.near_clip = camera.near;
  lens.far_clip = camera.far;
  viewer::Viewpoint v;
  v.view = eye_from_camera * world_from_camera.inverse().matrix();
  v.projection = lens.Projection(static_cast<double>(camera.width) / camera.height);
  v.eye = world_from_camera.translation();
  // The ground is drawn 20 distances around the point looked at: past far.
  v.distance = camera.far / 20;
  v.looked_at = v.eye + v.distance * world_from_camera.linear().col(2);
  return v;
}

bool FrameSchedule::Due(int64_t step) {
  const int64_t frame = step / period_;
  if (frame < last_frame_) last_frame_ = -1;  // a reset: the count starts again
  if (frame == last_frame_) return false;
  due_ += last_frame_ < 0 ? 1 : frame - last_frame_;
  last_frame_ = frame;
  return true;
}

float DepthMetres(float buffer_depth, double near, double far) {
  if (buffer_depth >= 1.0f) return std::numeric_limits<float>::infinity();
  // Inverse of the perspective depth mapping of gluPerspective.
  const double ndc = 2.0 * buffer_depth - 1.0;
  return static_cast<float>(2.0 * far * near / (far + near - ndc * (far - near)));
}

uint16_t DepthMillimetres(float metres) {
  if (!std::isfinite(metres) || metres <= 0 || metres * 1000.0f > 65535.0f) return 0;
  return static_cast<uint16_t>(std::lround(metres * 1000.0f));
}

std::vector<uint8_t> DepthBytes(const std::vector<float>& buffer_depth, const CameraSensor& camera) {
  std::vector<uint8_t> bytes;
  if (camera.depth == DepthFormat::kMetres) {
    bytes.resize(buffer_depth.size() * sizeof(float));
    for (size_t k = 0; k < buffer_depth.size(); ++k) {
      const float m = DepthMetres(buffer_depth[k], camera.near, camera.far);
      std::memcpy(bytes.data() + k * sizeof(float), &m, sizeof(float));  // little-endian host
    }
  } else if (camera.depth == DepthFormat::kMillimetres) {
    bytes.resize(buffer_depth.size() * sizeof(uint16_t));
    for (size_t k = 0; k < buffer_depth.size(); ++k) {
      const uint16_t mm = DepthMillimetres(DepthMetres(buffer_depth[k], camera.near, camera.far));
      std::memcpy(bytes.data() + k * sizeof(uint16_t), &mm, sizeof(uint16_t));
    }
  }
  return bytes;
}

}  // namespace simpartner::camera
