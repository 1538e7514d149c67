// Our worlds exported to MJCF: MuJoCo 2.2 (its C API, libmujoco) loads
// them with our masses and joints, and a pendulum and a sliding cube move
// the same in both simulators. Expected values are the closed forms of the
// worlds' own descriptions (models/worlds/pendulum.xml, sliding_cube.xml).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/convert/mjcf_export.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/simulation.h"

namespace simpartner::convert {
namespace {

const std::string kWorlds = std::string(SP_SOURCE_DIR) + "/models/worlds/";

struct MjModelFree {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataFree {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelFree>;
using MjDataPtr = std::unique_ptr<mjData, MjDataFree>;

model::World LoadWorld(const std::string& name) {
  model::WorldLoadResult loaded = model::LoadWorldFile(kWorlds + name);
  EXPECT_TRUE(loaded.world) << loaded.diagnostics.Format();
  return *loaded.world;
}

// MuJoCo reads MJCF from a file: the export goes through a temporary one.
MjModelPtr LoadInMujoco(const std::string& xml) {
  const std::string path =
      testing::TempDir() + "mjcf_" + std::to_string(getpid()) + ".xml";
  std::ofstream(path) << xml;
  char error[1000] = "";
  MjModelPtr model(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  std::filesystem::remove(path);
  EXPECT_TRUE(model) << "MuJoCo refused the MJCF: " << error << "\n" << xml;
  return model;
}

TEST(MjcfExport, Gen3LoadsInMujocoWithOurMassAndJoints) {
  const model::World world = LoadWorld("flat_ground.xml");  // gen3
  ASSERT_EQ(world.robots.size(), 1u);
  const model::Robot& robot = world.robots[0].robot;
  const MjcfExport exported = ExportMjcf(world, Parameters{});
  MjModelPtr m = LoadInMujoco(exported.xml);
  ASSERT_TRUE(m);
  double mujoco_mass = 0;
  for (int b = 0; b < m->nbody; ++b) mujoco_mass += m->body_mass[b];
  // SPEC 7: gen3 weighs 202 kg; both must say so.
  EXPECT_NEAR(robot.TotalMass(), 202.0, 1e-9);
  EXPECT_NEAR(mujoco_mass, 202.0, 1e-9);
  EXPECT_EQ(m->nbody, static_cast<int>(robot.bodies.size()) + 1);  // + worldbody
  // Every moving joint of ours, by name, plus the one free joint of the
  // robot's floating base; fixed joints weld bodies and have none.
  int moving = 0;
  for (const model::Joint& joint : robot.joints) {
    if (joint.kind == model::JointKind::kFixed) continue;
    ++moving;
    EXPECT_GE(mj_name2id(m.get(), mjOBJ_JOINT, joint.name.c_str()), 0) << joint.name;
  }
  EXPECT_EQ(m->njnt, moving + 1);
  EXPECT_EQ(m->nu, static_cast<int>(robot.actuators.size()));
  // The header lists what did not carry over: the three sensors.
  EXPECT_NE(exported.xml.find("sensor 'Scanner'"), std::string::npos);
  // y-up to z-up: gravity points down MuJoCo's z.
  EXPECT_DOUBLE_EQ(m->opt.gravity[2], -9.81);
  EXPECT_DOUBLE_EQ(m->opt.timestep, 0.001);
}

// Times between successive turning points of a swing (where the rate
// changes sign), doubled: the period.
double PeriodFromRates(const std::vector<double>& rates, double dt) {
  std::vector<double> turns;
  for (size_t n = 1; n < rates.size(); ++n)
    if ((rates[n - 1] < 0) != (rates[n] < 0) && rates[n - 1] != 0) turns.push_back(n * dt);
  if (turns.size() < 3) return NAN;
  return 2 * (turns.back() - turns.front()) / static_cast<double>(turns.size() - 1);
}

// pendulum.xml: a 1 m, 1 kg rod released horizontal swings with period
// 1.933 s (its description derives it). Ours and MuJoCo's within 0.5 % of
// it and of each other, over two periods.
TEST(MjcfExport, PendulumSwingsWithTheSamePeriod) {
  const model::World world = LoadWorld("pendulum.xml");
  const double dt = 0.001;
  const int steps = 4200;
  sim::Simulation sim(world, Parameters{}, 1);
  const int pivot = sim.flat().FindJoint("", "Pivot");
  ASSERT_GE(pivot, 0);
  std::vector<double> ours;
  for (int n = 0; n < steps; ++n) {
    ASSERT_TRUE(sim.Step());
    ours.push_back(sim.engine().JointRate(pivot, 0));
  }
  MjModelPtr m = LoadInMujoco(ExportMjcf(world, Parameters{}).xml);
  ASSERT_TRUE(m);
  MjDataPtr d(mj_makeData(m.get()));
  const int joint = mj_name2id(m.get(), mjOBJ_JOINT, "Pivot");
  ASSERT_GE(joint, 0);
  std::vector<double> theirs;
  for (int n = 0; n < steps; ++n) {
    mj_step(m.get(), d.get());
    theirs.push_back(d->qvel[m->jnt_dofadr[joint]]);
  }
  const double our_period = PeriodFromRates(ours, dt);
  const double their_period = PeriodFromRates(theirs, dt);
  EXPECT_NEAR(our_period, 1.933, 1.933 * 0.005);
  EXPECT_NEAR(their_period, 1.933, 1.933 * 0.005);
  EXPECT_NEAR(our_period, their_period, 1.933 * 0.005);
  // The same direction of swing (joint values count alike): down first.
  EXPECT_EQ(ours[100] < 0, theirs[100] < 0);
}

// sliding_cube.xml: 1 kg cube at 10 m/s on mu 0.5 stops after
// v0^2 / (2 mu g) = 10.19 m. Both within 2 % of that and of each other.
TEST(MjcfExport, SlidingCubeStopsAtTheSameDistance) {
  const model::World world = LoadWorld("sliding_cube.xml");
  const int steps = 3000;  // it stops at 2.04 s
  sim::Simulation sim(world, Parameters{}, 1);
  const int cube = sim.flat().FindBody("", "Cube");
  const double our_start = sim.engine().ReadBody(cube).position.x();
  double our_highest = 0;
  for (int n = 0; n < steps; ++n) {
    ASSERT_TRUE(sim.Step());
    our_highest = std::max(our_highest, sim.engine().ReadBody(cube).position.y());
  }
  // Ours slides flat on the floor (centre 0.5 m up). MuJoCo's hops at these
  // contact settings (docs/convert.md), so only its distance is compared.
  EXPECT_LT(our_highest, 0.5 + 1e-3);
  const double ours = sim.engine().ReadBody(cube).position.x() - our_start;
  EXPECT_NEAR(sim.engine().ReadBody(cube).linear_velocity.norm(), 0.0, 1e-3);

  const MjcfExport exported = ExportMjcf(world, Parameters{});
  MjModelPtr m = LoadInMujoco(exported.xml);
  ASSERT_TRUE(m);
  ASSERT_EQ(m->nkey, 1);  // the initial velocity
  MjDataPtr d(mj_makeData(m.get()));
  mj_resetDataKeyframe(m.get(), d.get(), 0);
  const int body = mj_name2id(m.get(), mjOBJ_BODY, "Cube");
  ASSERT_GE(body, 0);
  mj_forward(m.get(), d.get());
  const double their_start = d->xpos[3 * body];
  EXPECT_DOUBLE_EQ(d->qvel[0], 10.0);
  for (int n = 0; n < steps; ++n) mj_step(m.get(), d.get());
  const double theirs = d->xpos[3 * body] - their_start;
  const double expected = 10.0 * 10.0 / (2 * 0.5 * 9.81);
  EXPECT_NEAR(ours, expected, expected * 0.02);
  EXPECT_NEAR(theirs, expected, expected * 0.02);
  EXPECT_NEAR(ours, theirs, expected * 0.02);
}

// What MuJoCo cannot take is named in the header: an anisotropic
// friction (mu2) and a bounce; the lower friction wins a contact in both.
TEST(MjcfExport, HeaderListsWhatDidNotCarryOver) {
  const std::string xml =
      "<world name='Materials'>\n"
      "  <surface material='ice'><a>0</a><b>1</b><c>0</c><d>0</d></surface>\n"
      "  <material name='ice'><mu>0.05</mu></material>\n"
      "  <material name='tread'><mu>0.8</mu><mu2>0.3</mu2>"
      "<frictionDirection>rolling</frictionDirection><bounce>0.5</bounce></material>\n"
      "  <object type='Cylinder' name='Block' material='tread'><mass>1</mass>\n"
      "    <radius>0.1</radius><length>0.2</length>\n"
      "    <transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>\n"
      "      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.1</T13>\n"
      "      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation>\n"
      "  </object>\n"
      "</world>\n";
  model::WorldLoadResult loaded = model::ParseWorld(xml, "materials.xml");
  ASSERT_TRUE(loaded.world) << loaded.diagnostics.Format();
  const MjcfExport exported = ExportMjcf(*loaded.world, Parameters{});
  const std::string header = exported.xml.substr(0, exported.xml.find("-->"));
  EXPECT_NE(header.find("material 'tread': mu2 0.3"), std::string::npos) << header;
  EXPECT_NE(header.find("material 'tread': bounce 0.5"), std::string::npos) << header;
  MjModelPtr m = LoadInMujoco(exported.xml);
  ASSERT_TRUE(m);
  const int ground = mj_name2id(m.get(), mjOBJ_GEOM, "ground");
  const int block = mj_name2id(m.get(), mjOBJ_GEOM, "Block");
  ASSERT_GE(ground, 0);
  ASSERT_GE(block, 0);
  // Ours takes the smaller mu of a pair; MuJoCo the higher priority's.
  EXPECT_DOUBLE_EQ(m->geom_friction[3 * ground], 0.05);
  EXPECT_GT(m->geom_priority[ground], m->geom_priority[block]);
}

// A robot file on its own exports too: the robot, no ground.
TEST(MjcfExport, RobotFileAloneExports) {
  model::RobotLoadResult robot =
      model::LoadRobotFile(std::string(SP_SOURCE_DIR) + "/models/robots/workpartner_gen4.xml");
  ASSERT_TRUE(robot.robot) << robot.diagnostics.Format();
  MjModelPtr m = LoadInMujoco(ExportMjcf(WorldOfRobot(*robot.robot), Parameters{}).xml);
  ASSERT_TRUE(m);
  double mass = 0;
  for (int b = 0; b < m->nbody; ++b) mass += m->body_mass[b];
  // SPEC 8 / gen4_flat.xml: the validation model weighs 275.15 kg.
  EXPECT_NEAR(mass, 275.15, 1e-9);
  int shapes = 0;
  for (const model::Body& body : robot.robot->bodies)
    shapes += body.geometry.kind != model::GeometryKind::kNone;
  EXPECT_EQ(m->ngeom, shapes);  // no ground
}

}  // namespace
}  // namespace simpartner::convert

namespace simpartner::convert {
namespace {

// MuJoCo has no soil: the export says so in its header instead of
// dropping it silently.
TEST(MjcfExport, ASoilGroundIsSaidToBeRigidInTheMjcf) {
  const std::string xml =
      "<world name=\"Sand\">\n"
      "  <surface material=\"sand\"><a>0</a><b>1</b><c>0</c><d>0</d></surface>\n"
      "  <material name=\"sand\"><soil><n>1.1</n><kc>0.99</kc><kphi>1528.43</kphi>"
      "<cohesion>1.04</cohesion><frictionAngle>28</frictionAngle><shearModulus>0.025"
      "</shearModulus><unloadingStiffness>10000</unloadingStiffness><viscosity>0</viscosity>"
      "</soil></material>\n"
      "</world>\n";
  model::WorldLoadResult loaded = model::ParseWorld(xml, "sand.xml");
  ASSERT_TRUE(loaded.world) << loaded.diagnostics.Format();
  const MjcfExport exported = ExportMjcf(*loaded.world, Parameters{});
  const std::string header = exported.xml.substr(0, exported.xml.find("-->"));
  EXPECT_NE(header.find("material 'sand': soil 'sand' (MuJoCo has no soil model"),
            std::string::npos)
      << header;
}

}  // namespace
}  // namespace simpartner::convert
