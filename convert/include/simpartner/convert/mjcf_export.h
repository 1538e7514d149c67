// Our world (with its robots) to MJCF for MuJoCo 2.2. Our worlds are y-up
// (x forward, y up, z right); MuJoCo is z-up, so every world position and
// direction v becomes (v.x, -v.z, v.y). Bodies keep their own axes, so box
// half-sizes and cylinder axes (z) carry over unchanged. What MuJoCo has no
// place for is listed in the output's header comment. docs/convert.md
// derives each mapping.
#pragma once

#include <string>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/parameters.h"

namespace simpartner::convert {

// Actuator gains MuJoCo needs and our motors do not have (ODE's motors
// reach their velocity within one step up to their force limit; a MuJoCo
// servo is a spring or damper with a gain). Chosen stable with Euler at
// 1 ms on the WorkPartner's lightest parts (a 0.75 kg claw half).
struct MjcfGains {
  double position_kp = 5000;      // [N m/rad] angle controllers
  double position_damping = 50;   // [N m s/rad] joint damping on angle-controlled joints
  double velocity_kv = 100;       // [N m s/rad] joint (velocity) controllers, linear motors
  double force_limit = 1000;      // [N m] or [N], SPEC 4's hold force
};

struct MjcfExport {
  std::string xml;
  std::vector<std::string> not_carried;  // also in the header comment
  // MuJoCo names, in the order MuJoCo numbers them, for callers that map
  // our elements to MuJoCo ids: bodies (flat index order of ours).
  std::vector<std::string> body_names;
};

// world as loaded by our loader; params gives the step size and the
// contact defaults of geoms without a material. Throws ConvertError when
// the world cannot be expressed at all.
MjcfExport ExportMjcf(const model::World& world, const Parameters& params,
                      const MjcfGains& gains = {});

// A robot on its own (no ground, gravity -y) as a world, for exporting a
// robot file.
model::World WorldOfRobot(const model::Robot& robot);

// The y-up (ours) to z-up (MuJoCo) rotation: (x, y, z) -> (x, -z, y).
Eigen::Matrix3d YUpToZUp();

}  // namespace simpartner::convert
