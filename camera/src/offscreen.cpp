#include "simpartner/camera/offscreen.h"

// Framebuffer objects (GL 3.0, ARB_framebuffer_object) are called
// directly (GL_GLEXT_PROTOTYPES, sp_render's definition): libGL (glvnd)
// exports them, and llvmpipe and every desktop driver have them.
#include <SDL2/SDL_opengl.h>

#include <stdexcept>
#include <string>

namespace simpartner::camera {

struct OffscreenRenderer::Target {
  GLuint framebuffer = 0;
  GLuint colour = 0;
  GLuint depth = 0;

  Target(int width, int height) {
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glGenRenderbuffers(1, &colour);
    glBindRenderbuffer(GL_RENDERBUFFER, colour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      Release();
      throw std::runtime_error("the OpenGL driver cannot render a " + std::to_string(width) + "x" +
                               std::to_string(height) +
                               " framebuffer object (status " + std::to_string(status) + ")");
    }
  }
  ~Target() { Release(); }
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;

  void Release() {
    if (depth != 0) glDeleteRenderbuffers(1, &depth);
    if (colour != 0) glDeleteRenderbuffers(1, &colour);
    if (framebuffer != 0) glDeleteFramebuffers(1, &framebuffer);
    depth = colour = framebuffer = 0;
  }
};

OffscreenRenderer::OffscreenRenderer() {
  GLint side = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &side);
  if (glGetError() != GL_NO_ERROR || side <= 0)
    throw std::runtime_error("the OpenGL driver has no framebuffer objects (GL 3.0)");
  max_side_ = side;
}

OffscreenRenderer::~OffscreenRenderer() = default;

OffscreenRenderer::Target& OffscreenRenderer::TargetOfSize(int width, int height) {
  std::unique_ptr<Target>& target = targets_[{width, height}];
  if (!target) target = std::make_unique<Target>(width, height);
  return *target;
}

Frame OffscreenRenderer::Render(const viewer::Scene& scene, const CameraSensor& camera) {
  Target& target = TargetOfSize(camera.width, camera.height);
  glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
  // What a camera sees: bodies and ground, no grid, rays, arrows or text.
  viewer::Toggles plain;
  plain.grid = false;
  plain.scanner_rays = false;
  plain.hud = false;
  plain.follow = false;
  renderer_.Draw(scene, CameraViewpoint(camera, scene.BodyPose(camera.body)), plain,
                 viewer::Hud{}, camera.width, camera.height);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  Frame frame;
  frame.rgb = viewer::ReadRgb(camera.width, camera.height);
  if (camera.depth != DepthFormat::kNone)
    frame.depth_buffer = viewer::ReadDepth(camera.width, camera.height);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return frame;
}

}  // namespace simpartner::camera
