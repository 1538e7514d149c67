// Renders a camera's view offscreen: a framebuffer object per image size
// (colour and 24-bit depth renderbuffers) drawn by the viewer's Renderer
// with its overlays off. Needs a current GL context (a hidden GlWindow)
// for its whole life.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "simpartner/camera/camera_sensor.h"
#include "simpartner/viewer/renderer.h"
#include "simpartner/viewer/scene.h"

namespace simpartner::camera {

struct Frame {
  RgbImage rgb;            // rows top to bottom
  std::vector<float> depth_buffer; // 0 near .. 1 far, rows top to bottom; empty without depth
};

class OffscreenRenderer {
 public:
  // Throws std::runtime_error when the driver has no framebuffer objects.
  OffscreenRenderer();
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  // The largest image side the driver renders (GL_MAX_RENDERBUFFER_SIZE).
  int max_side() const { return max_side_; }
  // The scene's current state as `camera` sees it (its body's pose in the
  // scene's newest state).
  Frame Render(const viewer::Scene& scene, const CameraSensor& camera);

 private:
  struct Target;
  Target& TargetOfSize(int width, int height);

  viewer::Renderer renderer_;
  int max_side_ = 0;
  std::map<std::pair<int, int>, std::unique_ptr<Target>> targets_;
};

}  // namespace simpartner::camera
