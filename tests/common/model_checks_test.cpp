// Every rule of CheckModel (message_checks.h), one case each:
// a good message is taken, and the same message with one field damaged is
// refused with a problem that names that field and its value.
#include "simpartner/message_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "../support/non_finite.h"
#include "expect_problem.h"

namespace simpartner {
namespace {

using test_support::kInf;
using test_support::kNaN;
const std::string kBadUtf8("\xff\xfe", 2);

// Robot "Bot": box "Base" and sphere "Ball" on hinge "Swing", a scanner on
// Base, a motor on Swing, one material, a 2 x 3 heightfield.
model_t GoodModel() {
  model_t m{};
  m.simulation_id = 7;
  m.sender = "simpartner-sim@host:1";
  m.engine = "ode";
  m.step_size = 0.001;
  m.state_every = 1;
  m.gravity[1] = -9.81;
  m.up[1] = 1;
  m.has_plane = true;
  m.plane[1] = 1;
  material_t mat{};
  mat.name = "Rubber";
  mat.mu = 1;
  m.materials = {mat};
  m.num_materials = 1;
  robot_t r{};
  r.name = "Bot";
  m.robots = {r};
  m.num_robots = 1;
  for (int i = 0; i < 2; ++i) {
    body_t b{};
    b.id = i;
    b.name = i == 0 ? "Base" : "Ball";
    b.robot = 0;
    b.mass = 1;
    b.geometry.kind = i == 0 ? geometry_t::KIND_BOX : geometry_t::KIND_SPHERE;
    b.geometry.size[0] = 0.5;
    if (i == 0) b.geometry.size[1] = b.geometry.size[2] = 1;
    b.initial_orientation[0] = 1;
    m.bodies.push_back(b);
  }
  m.num_bodies = 2;
  joint_t j{};
  j.name = "Swing";
  j.body1 = 1;
  j.body2 = 0;
  j.lo_stop[0] = -kInf;  // free: infinite stops are allowed
  j.hi_stop[0] = kInf;
  m.joints = {j};
  m.num_joints = 1;
  sensor_t s{};
  s.name = "Scanner";
  s.kind = sensor_t::KIND_SCANNER;
  s.body = 0;
  s.joint = -1;
  s.orientation[0] = 1;
  s.params = {3, 1, 5};
  s.num_params = 3;
  m.sensors = {s};
  m.num_sensors = 1;
  actuator_t a{};
  a.name = "Motor";
  a.joint = 0;
  m.actuators = {a};
  m.num_actuators = 1;
  heightfield_t& h = m.heightfield;
  h.present = true;
  h.rows = 2;
  h.columns = 3;
  h.width = h.depth = 4;
  h.scale = 1;
  h.samples.assign(6, 0.5f);
  h.num_samples = 6;
  return m;
}

struct ModelCase {
  const char* rule;
  std::function<void(model_t*)> damage;
  const char* field;     // MessageProblem::field
  const char* message;   // found in MessageProblem::message
  MessageFault fault;
};

TEST(CheckModel, TakesAGoodModel) {
  EXPECT_FALSE(CheckModel(GoodModel())) << CheckModel(GoodModel())->message;
}

TEST(CheckModel, RefusesEachBrokenRuleNamingTheField) {
  using F = MessageFault;
  const std::vector<ModelCase> cases = {
      {"state_every >= 1", [](model_t* m) { m->state_every = 0; }, "state_every",
       "state_every = 0 (must be >= 1)", F::kOutOfRange},
      {"step_size > 0", [](model_t* m) { m->step_size = -1; }, "step_size",
       "step_size = -1 (must be a positive number)", F::kOutOfRange},
      {"gravity finite", [](model_t* m) { m->gravity[2] = kNaN; }, "gravity[2]",
       "gravity[2] = nan", F::kNonFinite},
      {"up unit", [](model_t* m) { m->up[1] = 0; }, "up", "up = (0, 0, 0) is not a unit vector",
       F::kNotUnit},
      {"plane finite", [](model_t* m) { m->plane[3] = kInf; }, "plane[3]", "plane[3] = inf",
       F::kNonFinite},
      {"plane normal not zero", [](model_t* m) { m->plane[1] = 0; }, "plane",
       "plane normal (a, b, c) is zero", F::kOutOfRange},
      {"host text", [](model_t* m) { m->host = kBadUtf8; }, "host",
       "host is not valid UTF-8 of at most 255 bytes (2 bytes)", F::kBadText},
      {"sender text", [](model_t* m) { m->sender = std::string(256, 's'); }, "sender",
       "sender is not valid UTF-8 of at most 255 bytes (256 bytes)", F::kBadText},
      {"engine text", [](model_t* m) { m->engine = std::string(33, 'e'); }, "engine",
       "engine is not valid UTF-8 of at most 32 bytes (33 bytes)", F::kBadText},
      {"world_file text", [](model_t* m) { m->world_file = std::string(1025, 'f'); },
       "world_file", "at most 1024 bytes", F::kBadText},
      {"world_name text", [](model_t* m) { m->world_name = kBadUtf8; }, "world_name",
       "world_name is not valid UTF-8", F::kBadText},
      {"parameters text", [](model_t* m) { m->parameters = kBadUtf8; }, "parameters",
       "parameters is not valid UTF-8 of at most 65535 bytes", F::kBadText},
      {"plane_material text", [](model_t* m) { m->plane_material = kBadUtf8; },
       "plane_material", "plane_material is not valid UTF-8", F::kBadText},
      {"robot name text", [](model_t* m) { m->robots[0].name = kBadUtf8; }, "robots[0].name",
       "robots[0].name is not valid UTF-8", F::kBadText},
      {"robot model text", [](model_t* m) { m->robots[0].model = kBadUtf8; },
       "robots[0].model", "robots[0].model is not valid UTF-8", F::kBadText},
      {"robot file text", [](model_t* m) { m->robots[0].file = kBadUtf8; }, "robots[0].file",
       "robots[0].file is not valid UTF-8 of at most 1024 bytes", F::kBadText},
      {"robot total_mass finite", [](model_t* m) { m->robots[0].total_mass = kNaN; },
       "robots[0].total_mass", "robots[0].total_mass = nan", F::kNonFinite},
      {"material name text", [](model_t* m) { m->materials[0].name = kBadUtf8; },
       "materials[0].name", "materials[0].name is not valid UTF-8", F::kBadText},
      {"material soil_name text", [](model_t* m) { m->materials[0].soil_name = kBadUtf8; },
       "materials[0].soil_name", "materials[0].soil_name is not valid UTF-8", F::kBadText},
      {"material numbers finite", [](model_t* m) { m->materials[0].soil_viscosity = kInf; },
       "materials[0].soil_viscosity", "materials[0].soil_viscosity = inf", F::kNonFinite},
      {"material friction_direction known",
       [](model_t* m) { m->materials[0].friction_direction = 5; },
       "materials[0].friction_direction",
       "materials[0].friction_direction = 5 (FRICTION_SLIP or FRICTION_ROLLING)",
       F::kUnknownValue},
      {"body robot index", [](model_t* m) { m->bodies[1].robot = 1; }, "bodies[1].robot",
       "bodies[1].robot = 1 (no such robot), the model has 1", F::kBadIndex},
      {"body name text", [](model_t* m) { m->bodies[0].name = kBadUtf8; }, "bodies[0].name",
       "bodies[0].name is not valid UTF-8", F::kBadText},
      {"body material text", [](model_t* m) { m->bodies[0].material = kBadUtf8; },
       "bodies[0].material", "bodies[0].material is not valid UTF-8", F::kBadText},
      {"geometry sizes finite", [](model_t* m) { m->bodies[1].geometry.size[2] = kNaN; },
       "bodies[1].geometry.size[2]", "bodies[1].geometry.size[2] = nan", F::kNonFinite},
      {"geometry kind known", [](model_t* m) { m->bodies[1].geometry.kind = 42; },
       "bodies[1].geometry.kind", "bodies[1].geometry.kind = 42 (not a geometry_t.KIND_*)",
       F::kUnknownValue},
      {"geometry size above 0", [](model_t* m) { m->bodies[0].geometry.size[1] = -2; },
       "bodies[0].geometry.size[1]", "bodies[0].geometry.size[1] = -2 (above 0 to 100000 m)",
       F::kOutOfRange},
      {"geometry size at most 100 km", [](model_t* m) { m->bodies[1].geometry.size[0] = 1e6; },
       "bodies[1].geometry.size[0]", "bodies[1].geometry.size[0] = 1e+06", F::kOutOfRange},
      {"body mass finite", [](model_t* m) { m->bodies[0].mass = kNaN; }, "bodies[0].mass",
       "bodies[0].mass = nan", F::kNonFinite},
      {"body com finite", [](model_t* m) { m->bodies[0].com[1] = kInf; }, "bodies[0].com[1]",
       "bodies[0].com[1] = inf", F::kNonFinite},
      {"body inertia finite", [](model_t* m) { m->bodies[0].inertia[5] = kNaN; },
       "bodies[0].inertia[5]", "bodies[0].inertia[5] = nan", F::kNonFinite},
      {"body initial_position finite", [](model_t* m) { m->bodies[1].initial_position[0] = kNaN; },
       "bodies[1].initial_position[0]", "bodies[1].initial_position[0] = nan", F::kNonFinite},
      {"body initial_orientation unit",
       [](model_t* m) { m->bodies[1].initial_orientation[0] = 1.7; },
       "bodies[1].initial_orientation",
       "bodies[1].initial_orientation has length 1.7 (a unit quaternion is needed)",
       F::kNotUnit},
      {"joint robot index", [](model_t* m) { m->joints[0].robot = -2; }, "joints[0].robot",
       "joints[0].robot = -2 (no such robot)", F::kBadIndex},
      {"joint body1 index", [](model_t* m) { m->joints[0].body1 = 7; }, "joints[0].body1",
       "joints[0].body1 = 7 (no such body)", F::kBadIndex},
      {"joint body2 index", [](model_t* m) { m->joints[0].body2 = 2; }, "joints[0].body2",
       "joints[0].body2 = 2 (no such body), the model has 2", F::kBadIndex},
      {"joint name text", [](model_t* m) { m->joints[0].name = kBadUtf8; }, "joints[0].name",
       "joints[0].name is not valid UTF-8", F::kBadText},
      {"joint anchor finite", [](model_t* m) { m->joints[0].anchor[0] = kNaN; },
       "joints[0].anchor[0]", "joints[0].anchor[0] = nan", F::kNonFinite},
      {"joint axis finite", [](model_t* m) { m->joints[0].axis[1][2] = kInf; },
       "joints[0].axis[1][2]", "joints[0].axis[1][2] = inf", F::kNonFinite},
      {"joint lo_stop not NaN", [](model_t* m) { m->joints[0].lo_stop[1] = kNaN; },
       "joints[0].lo_stop[1]", "joints[0].lo_stop[1] = nan", F::kNonFinite},
      {"joint hi_stop not NaN", [](model_t* m) { m->joints[0].hi_stop[2] = kNaN; },
       "joints[0].hi_stop[2]", "joints[0].hi_stop[2] = nan", F::kNonFinite},
      {"sensor robot index", [](model_t* m) { m->sensors[0].robot = 3; }, "sensors[0].robot",
       "sensors[0].robot = 3 (no such robot)", F::kBadIndex},
      {"sensor body index", [](model_t* m) { m->sensors[0].body = 2; }, "sensors[0].body",
       "sensors[0].body = 2 (no such body)", F::kBadIndex},
      {"sensor joint index", [](model_t* m) { m->sensors[0].joint = 99; }, "sensors[0].joint",
       "sensors[0].joint = 99 (no such joint)", F::kBadIndex},
      {"sensor name text", [](model_t* m) { m->sensors[0].name = kBadUtf8; }, "sensors[0].name",
       "sensors[0].name is not valid UTF-8", F::kBadText},
      {"sensor position finite", [](model_t* m) { m->sensors[0].position[1] = kNaN; },
       "sensors[0].position[1]", "sensors[0].position[1] = nan", F::kNonFinite},
      {"sensor orientation unit", [](model_t* m) { m->sensors[0].orientation[0] = 0; },
       "sensors[0].orientation", "sensors[0].orientation has length 0", F::kNotUnit},
      {"sensor rate finite", [](model_t* m) { m->sensors[0].rate = kInf; }, "sensors[0].rate",
       "sensors[0].rate = inf", F::kNonFinite},
      {"sensor params finite", [](model_t* m) { m->sensors[0].params[2] = kNaN; },
       "sensors[0].params[2]", "sensors[0].params[2] = nan", F::kNonFinite},
      {"actuator robot index", [](model_t* m) { m->actuators[0].robot = 4; },
       "actuators[0].robot", "actuators[0].robot = 4 (no such robot)", F::kBadIndex},
      {"actuator joint index", [](model_t* m) { m->actuators[0].joint = 1; },
       "actuators[0].joint", "actuators[0].joint = 1 (no such joint)", F::kBadIndex},
      {"actuator name text", [](model_t* m) { m->actuators[0].name = kBadUtf8; },
       "actuators[0].name", "actuators[0].name is not valid UTF-8", F::kBadText},
      {"heightfield at least 2 x 2", [](model_t* m) { m->heightfield.rows = 1; },
       "heightfield.rows", "heightfield.rows = 1, columns = 3 (at least 2 x 2 samples)",
       F::kOutOfRange},
      {"heightfield at most 16 Mi samples",
       [](model_t* m) { m->heightfield.rows = m->heightfield.columns = 5000; },
       "heightfield.rows", "heightfield.rows x columns = 25000000 samples (at most 16777216)",
       F::kOutOfRange},
      {"heightfield samples match rows x columns",
       [](model_t* m) {
         m->heightfield.samples.resize(5);
         m->heightfield.num_samples = 5;
       },
       "heightfield.num_samples", "heightfield.num_samples = 5 but rows x columns = 6",
       F::kCountMismatch},
      {"heightfield width in range", [](model_t* m) { m->heightfield.width = 0; },
       "heightfield.width", "heightfield.width = 0 (above 0 to 100000 m)", F::kOutOfRange},
      {"heightfield depth in range", [](model_t* m) { m->heightfield.depth = kNaN; },
       "heightfield.depth", "heightfield.depth = nan", F::kOutOfRange},
      {"heightfield scale finite", [](model_t* m) { m->heightfield.scale = kInf; },
       "heightfield.scale", "heightfield.scale = inf", F::kNonFinite},
      {"heightfield offset finite", [](model_t* m) { m->heightfield.offset = kNaN; },
       "heightfield.offset", "heightfield.offset = nan", F::kNonFinite},
      {"heightfield thickness finite", [](model_t* m) { m->heightfield.thickness = kNaN; },
       "heightfield.thickness", "heightfield.thickness = nan", F::kNonFinite},
      {"heightfield position finite", [](model_t* m) { m->heightfield.position[1] = kNaN; },
       "heightfield.position[1]", "heightfield.position[1] = nan", F::kNonFinite},
      {"heightfield material text", [](model_t* m) { m->heightfield.material = kBadUtf8; },
       "heightfield.material", "heightfield.material is not valid UTF-8", F::kBadText},
      {"heightfield samples finite",
       [](model_t* m) { m->heightfield.samples[4] = std::numeric_limits<float>::infinity(); },
       "heightfield.samples[4]", "heightfield.samples[4] = inf", F::kNonFinite},
  };
  for (const ModelCase& c : cases) {
    model_t m = GoodModel();
    c.damage(&m);
    testing::ExpectProblem(CheckModel(m), c.rule, "model_t", c.field, c.fault, c.message);
  }
}

TEST(CheckModel, ACapsuleMayHaveNoCylinderPartAndNamesItsElement) {
  model_t m = GoodModel();
  m.bodies[1].geometry.kind = geometry_t::KIND_CAPSULE;
  m.bodies[1].geometry.size[1] = 0;
  EXPECT_FALSE(CheckModel(m));
  m.bodies[1].geometry.size[0] = 0;
  const MessageCheck problem = CheckModel(m);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->array, "bodies");
  EXPECT_EQ(problem->index, 1);
  EXPECT_EQ(problem->Format(), "model_t.bodies[1].geometry.size[0] = 0 (above 0 to 100000 m)");
}

TEST(OutlineOf, KeepsCountsAndSensors) {
  const ModelOutline outline = OutlineOf(GoodModel());
  EXPECT_EQ(outline.simulation_id, 7);
  EXPECT_EQ(outline.bodies, 2);
  EXPECT_EQ(outline.joints, 1);
  ASSERT_EQ(outline.sensors.size(), 1u);
  EXPECT_EQ(outline.sensors[0].name, "Scanner");
  EXPECT_EQ(outline.sensors[0].kind, sensor_t::KIND_SCANNER);
}

}  // namespace
}  // namespace simpartner
