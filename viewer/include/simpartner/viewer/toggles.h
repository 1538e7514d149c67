// What the renderer draws besides the bodies and the ground: the viewer
// toggles each with a key (keys.h); simpartner-camera turns the overlays off.
#pragma once

namespace simpartner::viewer {

// What is drawn; each has a key that toggles it (see keys.h).
struct Toggles {
  bool wireframe = false;
  bool body_frames = false;
  bool contact_forces = false;
  bool joint_forces = false;
  bool scanner_rays = true;
  bool grid = true;
  bool hud = true;
  bool key_help = false;
  bool follow = true;  // camera follows robot 0
};

}  // namespace simpartner::viewer
