// Small hand-made messages for the viewer's unit tests: a model with a box,
// a sphere on a hinge and a scanner, and states that fit it.
#pragma once

#include <cmath>

#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner::viewer::testing {

// Robot "Bot" of two bodies: Base (box 1 x 2 x 1 at (0, 1, 0)) and Ball
// (sphere r 0.25 at (2, 1, 0)), joined by hinge "Swing"; a scanner on Base.
inline model_t TwoBodyModel(int64_t simulation_id) {
  model_t m{};
  m.simulation_id = simulation_id;
  m.world_name = "UnitWorld";
  m.step_size = 0.001;
  m.state_every = 1;
  m.gravity[1] = -9.81;
  m.up[1] = 1;
  m.has_plane = true;
  m.plane[1] = 1;
  robot_t r{};
  r.name = "Bot";
  r.model = "Bot model";
  m.robots = {r};
  m.num_robots = 1;
  for (int i = 0; i < 2; ++i) {
    body_t b{};
    b.id = i;
    b.name = i == 0 ? "Base" : "Ball";
    b.robot = 0;
    b.mass = 1;
    b.geometry.kind = i == 0 ? geometry_t::KIND_BOX : geometry_t::KIND_SPHERE;
    if (i == 0) {
      b.geometry.size[0] = 1;
      b.geometry.size[1] = 2;
      b.geometry.size[2] = 1;
    } else {
      b.geometry.size[0] = 0.25;
    }
    b.initial_position[0] = i == 0 ? 0 : 2;
    b.initial_position[1] = 1;
    b.initial_orientation[0] = 1;
    m.bodies.push_back(b);
  }
  m.num_bodies = 2;
  joint_t j{};
  j.name = "Swing";
  j.robot = 0;
  j.kind = joint_t::KIND_HINGE;
  j.body1 = 1;
  j.body2 = 0;
  j.num_axes = 1;
  m.joints = {j};
  m.num_joints = 1;
  sensor_t s{};
  s.id = 0;
  s.name = "Scanner";
  s.robot = 0;
  s.kind = sensor_t::KIND_SCANNER;
  s.body = 0;
  s.joint = -1;
  s.orientation[0] = 1;
  s.params = {3, 0.1, 10};
  s.num_params = 3;
  m.sensors = {s};
  m.num_sensors = 1;
  return m;
}

inline state_t StateFor(const model_t& m, int64_t step) {
  state_t s{};
  s.simulation_id = m.simulation_id;
  s.step = step;
  s.sim_time = step * m.step_size;
  s.bodies.resize(static_cast<size_t>(m.num_bodies));
  for (int i = 0; i < m.num_bodies; ++i) {
    body_state_t& b = s.bodies[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k) b.position[k] = m.bodies[static_cast<size_t>(i)].initial_position[k];
    b.orientation[0] = 1;
  }
  s.num_bodies = m.num_bodies;
  s.joints.resize(static_cast<size_t>(m.num_joints));
  s.num_joints = m.num_joints;
  return s;
}

inline sensor_reading_t ScanFor(const model_t& m, std::vector<double> ranges) {
  sensor_reading_t r{};
  r.simulation_id = m.simulation_id;
  r.sensor = 0;
  r.name = "Scanner";
  r.kind = sensor_t::KIND_SCANNER;
  r.values = std::move(ranges);
  r.num_values = static_cast<int32_t>(r.values.size());
  return r;
}

}  // namespace simpartner::viewer::testing
