// A world as the sim announces it on SIM_MODEL, built without a sim: names,
// kinds, legacy ports, initial poses, joint anchors and axes, sensors and
// actuators with their axis slots, materials. For checking files offline
// against a world (simpartner-sequencer --check, simpartner-teleop
// --check), where the same catalogue of targets is needed as from the bus.
// What only a built world knows (inertia, a run's simulation id,
// parameters) is left empty.
#pragma once

#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/model_t.hpp"

namespace simpartner::model {

// A material as SIM_MODEL carries it: mu2 = mu when isotropic, stiffness
// and damping 0 when the softness is given per step.
material_t MaterialMessage(const Material& material);

// sensor_t.KIND_* of a kind.
int8_t ToLcm(SensorKind kind);
// sensor_t.params of a sensor as its file gives it: the Scanner's rays,
// halfSpan, range; a new kind's parameters in SensorParameterSpecs order,
// a Gnss's followed by the world's geodetic origin (latitude, longitude
// [deg], altitude [m]).
std::vector<double> SensorParamsMessage(const Sensor& sensor, const World& world);
// A camera's sensor_t.params: width, height, fov, near, far, depth (0 none,
// 1 metres, 2 millimetres), as lcmtypes/sensor_t.lcm states.
std::vector<double> CameraParams(const CameraSettings& camera);

// World objects and joints first, then each robot's bodies, joints,
// actuators and sensors in file order, as the sim numbers them.
model_t ModelMessageFromWorld(const World& world);

}  // namespace simpartner::model
