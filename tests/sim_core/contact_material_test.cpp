// Materials with two friction coefficients (mu along the first friction
// direction, mu2 across it) and with a physical contact stiffness and
// damping (docs/contacts.md). Every expected number comes from Newton's
// laws, Coulomb friction or the mass-spring-damper, worked out here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_worlds.h"
#include "simpartner/text.h"

namespace simpartner::sim {
namespace {

using testing::MakeSim;
using testing::Transform;
using testing::Vec;

constexpr double kG = 9.81;

std::string Velocity(double vx, double vy, double vz) {
  return "<translationalVelocity><vx>" + ShortestNumber(vx) + "</vx><vy>" + ShortestNumber(vy) + "</vy><vz>" + ShortestNumber(vz) +
         "</vz></translationalVelocity>";
}

Parameters OnEngine(const std::string& engine, double h = 0.001) {
  Parameters params;
  params.engine = engine;
  params.stepsize = h;
  return params;
}

// Every law here is the physics', not an engine's: each test runs on both.
class ContactMaterial : public ::testing::TestWithParam<std::string> {
 protected:
  const std::string& engine() const { return GetParam(); }
};
INSTANTIATE_TEST_SUITE_P(Engines, ContactMaterial, ::testing::Values("ode", "mujoco"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

// ------------------------------------------------------------ friction

// A box of mass m and size (lx, ly, lz) on a plane of material `floor`,
// sliding at (vx, 0, vz); the box is of `box_material` ("": the default,
// mu = contactMu = 1 both ways).
std::string SlidingBoxWorld(const std::string& material, double mass, double lx, double ly,
                            double lz, double vx, double vz,
                            const std::string& box_material = "floor") {
  const std::string box_says =
      box_material.empty() ? std::string() : " material=\"" + box_material + "\"";
  return "<world name=\"Slide\"><surface material=\"floor\"><a>0</a><b>1</b><c>0</c><d>0</d>"
         "</surface>" + material +
         "<object type=\"Box\" name=\"Box\"" + box_says + "><mass>" + ShortestNumber(mass) + "</mass>" +
         Vec("size", lx, ly, lz) + Transform(0, ly / 2, 0) + Velocity(vx, 0, vz) +
         "</object></world>";
}

// The thesis's friction (0.5 along, 1.0 across) on a ground that asks for
// each wheel's rolling direction: a box has none, so the contact is
// isotropic Coulomb (mu2 is read across a rolling direction only): mu N
// against the slip whatever way it slides, and straight on.
TEST_P(ContactMaterial, BoxOnARollingGroundBrakesAtMuGWhateverTheHeading) {
  constexpr double kV0 = 3.0, kMu = 0.5, kT = 0.3;
  const std::string floor =
      "<material name=\"floor\"><mu>0.5</mu><mu2>1.0</mu2>"
      "<frictionDirection>rolling</frictionDirection></material>";
  const double expected_speed = kV0 - kMu * kG * kT;  // 1.5285 m/s
  for (const double degrees : {0.0, 30.0, 45.0, 110.0, 200.0}) {
    SCOPED_TRACE("heading " + std::to_string(degrees) + " deg");
    const double heading = degrees * M_PI / 180.0;
    auto sim = MakeSim(SlidingBoxWorld(floor, 1, 1, 1, 1, kV0 * std::cos(heading),
                                       kV0 * std::sin(heading), ""),
                       {}, OnEngine(engine()));
    for (int n = 0; n < 300; ++n) ASSERT_TRUE(sim->Step());
    const Eigen::Vector3d v = sim->engine().ReadBody(0).linear_velocity;
    EXPECT_NEAR(std::hypot(v.x(), v.z()), expected_speed, 0.01 * expected_speed);
    EXPECT_NEAR(std::atan2(v.z(), v.x()), std::atan2(std::sin(heading), std::cos(heading)), 1e-3);
  }
}

// A material that says mu2 = mu, or frictionDirection slip, is the
// isotropic material of old files, step for step.
TEST_P(ContactMaterial, ExplicitIsotropicMaterialIsBitIdenticalToTheOldForm) {
  const auto run = [this](const std::string& material) {
    auto sim = MakeSim(SlidingBoxWorld(material, 1, 1, 1, 1, 2.0, 1.0), {}, OnEngine(engine()));
    for (int n = 0; n < 200; ++n) EXPECT_TRUE(sim->Step());
    return sim->engine().ReadBody(0);
  };
  const BodyReadout old_form = run("<material name=\"floor\"><mu>0.5</mu></material>");
  const BodyReadout explicit_form = run(
      "<material name=\"floor\"><mu>0.5</mu><mu2>0.5</mu2>"
      "<frictionDirection>slip</frictionDirection></material>");
  EXPECT_EQ(old_form.position, explicit_form.position);
  EXPECT_EQ(old_form.linear_velocity, explicit_form.linear_velocity);
  EXPECT_EQ(old_form.contact_force, explicit_form.contact_force);
}

// The contact force on the box in the frame of its sliding velocity
// (along, across), horizontal components only, while a side force F pushes
// it across its initial slip.
struct SlipFrameForces {
  double along_mean = 0, across_mean = 0;
  double along_worst = 0, across_worst = 0;  // largest |x - mean| seen
  Eigen::Vector3d final_velocity = Eigen::Vector3d::Zero();
};

SlipFrameForces PushSideways(const std::string& engine, double side_force, int steps) {
  // A thin 10 kg plate (1 x 0.02 x 1 m) so that the side force hardly
  // shifts the load between its corners, of the default material, on a
  // ground of mu 0.2 along its wheels' rolling direction and 0.6 across.
  const std::string floor =
      "<material name=\"floor\"><mu>0.2</mu><mu2>0.6</mu2>"
      "<frictionDirection>rolling</frictionDirection></material>";
  // ODE softens the friction rows of a contact by the world's CFM: each
  // step a held friction force F lets the slip turn by CFM F (7e-5 m/s a
  // step here), which the next step's slip direction then keeps. This test
  // measures the friction law itself, so the world CFM is 1e-9 (0 would
  // leave the four corners' shares of the load undetermined; see
  // docs/contacts.md, "Known limits").
  Parameters params = OnEngine(engine);
  params.globalCFM = 1e-9;
  auto sim = MakeSim(SlidingBoxWorld(floor, 10, 1, 0.02, 1, 3.0, 0.0, ""), {}, params);
  SlipFrameForces out;
  std::vector<double> along, across;
  for (int n = 0; n < steps; ++n) {
    const Eigen::Vector3d v = sim->engine().ReadBody(0).linear_velocity;
    const Eigen::Vector3d dir = Eigen::Vector3d(v.x(), 0, v.z()).normalized();
    const Eigen::Vector3d side = Eigen::Vector3d::UnitY().cross(dir);  // dir turned by -90 deg
    sim->engine().AddForce(0, Eigen::Vector3d(0, 0, side_force));
    EXPECT_TRUE(sim->Step());
    if (n < 20) continue;  // the first contacts settle the plate
    const Eigen::Vector3d f = sim->engine().ReadBody(0).contact_force;
    along.push_back(f.dot(dir));
    across.push_back(f.dot(side));
  }
  auto mean = [](const std::vector<double>& x) {
    double sum = 0;
    for (double e : x) sum += e;
    return sum / static_cast<double>(x.size());
  };
  out.along_mean = mean(along);
  out.across_mean = mean(across);
  for (size_t i = 0; i < along.size(); ++i) {
    out.along_worst = std::max(out.along_worst, std::abs(along[i] - out.along_mean));
    out.across_worst = std::max(out.across_worst, std::abs(across[i] - out.across_mean));
  }
  out.final_velocity = sim->engine().ReadBody(0).linear_velocity;
  return out;
}

// The plate has no rolling direction, so its contact is isotropic: mu N
// against the slip and none across it, whatever the ground's mu2. A side
// push of 1.5 mu N turns the slide towards it. Until 2026-11-26 mu2 was
// read across the slip and held the push (0.5 mu2 N) with the slide going
// straight on: across_mean was the push and the final v_z 0. Tolerance 1 %.
TEST_P(ContactMaterial, PlateWithoutRollingDirectionTurnsAsCoulombsCone) {
  constexpr double kN = 10 * kG, kMu = 0.2;
  const double push = 1.5 * kMu * kN;  // 29.43 N, 0.5 mu2 N
  const SlipFrameForces f = PushSideways(engine(), push, 500);
  EXPECT_NEAR(f.along_mean, -kMu * kN, 0.01 * kMu * kN);
  EXPECT_LT(f.along_worst, 0.02 * kMu * kN);
  EXPECT_LT(std::abs(f.across_mean), 0.01 * kMu * kN);
  EXPECT_GT(f.final_velocity.z(), 0.5);  // the slip turned towards the push
  std::printf("push %.2f N: friction along the slip %.3f N (mu N = %.3f), across %.3f N\n", push,
              -f.along_mean, kMu * kN, f.across_mean);
}

// A driven wheel with a "rolling" tyre (mu 0.8 along its rolling
// direction, 0.4 across) on a 10 kg sled that lies on frictionless ice.
// The wheel (5 kg) hangs on a hinge from a 5 kg carrier that a vertical
// slider holds to the world, so the contact carries their weight N =
// 98.1 N and the wheel cannot move sideways. The wheel spins far faster
// than the sled can follow, so it slips: the sled is pulled along at
// mu N / M; a side push F on the sled is resisted by at most mu2 N.
std::string WheelOnSledWorld() {
  return "<world name=\"Sled\"><surface material=\"ice\"><a>0</a><b>1</b><c>0</c><d>0</d>"
         "</surface>"
         "<material name=\"ice\"><mu>0</mu></material>"
         "<material name=\"deck\"><mu>5</mu></material>"
         "<material name=\"tyre\"><mu>0.8</mu><mu2>0.4</mu2>"
         "<frictionDirection>rolling</frictionDirection></material>"
         "<object type=\"Box\" name=\"Sled\" material=\"deck\"><mass>10</mass>" +
         Vec("size", 8, 0.1, 4) + Transform(0, 0.05, 0) +
         "</object>"
         "<object type=\"Box\" name=\"Carrier\"><mass>5</mass>" +
         Vec("size", 0.2, 0.2, 0.2) + Transform(0, 1.0, 0) +
         "</object>"
         "<object type=\"Cylinder\" name=\"Wheel\" material=\"tyre\"><mass>5</mass>"
         "<radius>0.3</radius><length>0.2</length>" +
         Transform(0, 0.4, 0) +
         "</object>"
         "<joint type=\"Slider\" name=\"Hanger\"><body1>Carrier</body1><body2>world</body2>" +
         Vec("axis1", 0, 1, 0) +
         "</joint>"
         "<joint type=\"Hinge\" name=\"Axle\"><body1>Carrier</body1><body2>Wheel</body2>" +
         Vec("anchor", 0, 0.4, 0) + Vec("axis1", 0, 0, 1) + "</joint></world>";
}

TEST_P(ContactMaterial, RollingTyreDrivesWithMuNAndHoldsSidewaysWithMu2N) {
  constexpr double kN = 10 * kG, kMu = 0.8, kMu2 = 0.4;
  for (const double push : {0.75 * kMu2 * kN, 1.5 * kMu2 * kN}) {
    SCOPED_TRACE("side push " + std::to_string(push) + " N");
    auto sim = MakeSim(WheelOnSledWorld(), {}, OnEngine(engine()));
    const int sled = sim->flat().FindBody("", "Sled");
    const int axle = sim->flat().FindJoint("", "Axle");
    ASSERT_GE(sled, 0);
    ASSERT_GE(axle, 0);
    sim->engine().SetMotor(axle, 0, 60.0, 1e4);  // 18 m/s at the tread
    // The ice pushes the sled up only, so the horizontal contact force on
    // the sled is the tyre's friction. 0.2 s: the sled has moved 0.16 m,
    // too little for the off-centre side force to turn it noticeably.
    double traction = 0, side = 0;
    int counted = 0;
    for (int n = 0; n < 200; ++n) {
      sim->engine().AddForce(sled, Eigen::Vector3d(0, 0, push));
      ASSERT_TRUE(sim->Step());
      if (n < 20) continue;  // the wheel settles onto the sled
      const Eigen::Vector3d f = sim->engine().ReadBody(sled).contact_force;
      traction += std::abs(f.x());
      side += -f.z();
      ++counted;
    }
    traction /= counted;
    side /= counted;
    // Along the rolling direction (x) the tyre slips: mu N.
    EXPECT_NEAR(traction, kMu * kN, 0.01 * kMu * kN);
    // Across it (z): the push, or mu2 N when the push is larger.
    EXPECT_NEAR(side, std::min(push, kMu2 * kN), 0.01 * kMu2 * kN);
    std::printf("rolling tyre, push %.2f N: traction %.3f N (mu N = %.3f), side friction %.3f N "
                "(mu2 N = %.3f)\n",
                push, traction, kMu * kN, side, kMu2 * kN);
  }
}

// The ground may ask for the rolling direction of every wheel on it (a
// plane has no axis of its own): a 10 kg wheel hung from a carrier that a
// vertical slider holds, spun far faster than it can roll (it cannot move),
// on ground of mu 0.3 along the rolling direction and 0.9 across it, is
// braked by mu N along x (its rolling direction, the hinge being along z)
// and by nothing across it, with the axle along z and turned along x.
// (Here the tread also slides along its rolling direction, so "slip" would
// brake the same way: what tells the two apart is a vehicle whose wheels
// slide sideways, the validation's circles, tests/validate.) Before, a
// rolling ground stopped the sim at its construction.
TEST_P(ContactMaterial, GroundAsksForTheRollingDirectionOfTheWheelOnIt) {
  constexpr double kN = 10 * kG, kMu = 0.3;
  for (const bool axle_along_z : {true, false}) {
    SCOPED_TRACE(axle_along_z ? "axle along z" : "axle along x");
    const std::string axis = axle_along_z ? Vec("axis1", 0, 0, 1) : Vec("axis1", 1, 0, 0);
    // A cylinder's own axis is its z: for an axle along x it is turned 90
    // degrees about y (body z to world x), standing on its tread either way.
    const std::string placement =
        axle_along_z ? Transform(0, 0.3, 0)
                     : "<transformation><T00>0</T00><T01>0</T01><T02>1</T02><T03>0</T03>"
                       "<T10>0</T10><T11>1</T11><T12>0</T12><T13>0.3</T13>"
                       "<T20>-1</T20><T21>0</T21><T22>0</T22><T23>0</T23></transformation>";
    const std::string world =
        "<world name=\"Ground\"><surface material=\"ground\"><a>0</a><b>1</b><c>0</c><d>0</d>"
        "</surface>"
        "<material name=\"ground\"><mu>0.3</mu><mu2>0.9</mu2>"
        "<frictionDirection>rolling</frictionDirection></material>"
        "<object type=\"Box\" name=\"Carrier\"><mass>5</mass>" +
        Vec("size", 0.2, 0.2, 0.2) + Transform(0, 0.6, 0) +
        "</object>"
        "<object type=\"Cylinder\" name=\"Wheel\"><mass>5</mass>"
        "<radius>0.3</radius><length>0.2</length>" +
        placement +
        "</object>"
        "<joint type=\"Slider\" name=\"Hanger\"><body1>Carrier</body1><body2>world</body2>" +
        Vec("axis1", 0, 1, 0) +
        "</joint>"
        "<joint type=\"Hinge\" name=\"Axle\"><body1>Carrier</body1><body2>Wheel</body2>" +
        Vec("anchor", 0, 0.3, 0) + axis + "</joint></world>";
    auto sim = MakeSim(world, {}, OnEngine(engine()));
    const int wheel = sim->flat().FindBody("", "Wheel");
    const int axle = sim->flat().FindJoint("", "Axle");
    ASSERT_GE(wheel, 0);
    ASSERT_GE(axle, 0);
    sim->engine().SetMotor(axle, 0, 30.0, 1e4);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    int counted = 0;
    for (int n = 0; n < 200; ++n) {
      ASSERT_TRUE(sim->Step());
      if (n < 20) continue;  // settling onto the ground
      mean += sim->engine().ReadBody(wheel).contact_force;
      ++counted;
    }
    mean /= counted;
    const double along = axle_along_z ? mean.x() : mean.z();
    const double across = axle_along_z ? mean.z() : mean.x();
    EXPECT_NEAR(std::abs(along), kMu * kN, 0.01 * kMu * kN) << mean.transpose();
    EXPECT_NEAR(across, 0.0, 0.01 * kMu * kN) << mean.transpose();
  }
}

// ------------------------------------------------------------ stiffness

// A box of mass m, side s, of material `stiff` released on a plane of the
// default material with its bottom face 1e-7 m into it.
std::string BoxOnPlaneWorld(double stiffness, double damping, double mass, double side) {
  return "<world name=\"Sink\"><surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>"
         "<material name=\"stiff\"><stiffness>" + ShortestNumber(stiffness) + "</stiffness><damping>" +
         ShortestNumber(damping) + "</damping></material>"
         "<object type=\"Box\" name=\"Box\" material=\"stiff\"><mass>" + ShortestNumber(mass) + "</mass>" +
         Vec("size", side, side, side) + Transform(0, side / 2 - 1e-7, 0) + "</object></world>";
}

// A static contact is a spring: the box sinks m g / k at any step size.
TEST_P(ContactMaterial, StaticSinkIsMgOverKAtEveryStepSize) {
  constexpr double kMass = 10, kSide = 0.5, kK = 1e6;
  const double c = 2.0 * std::sqrt(kK * kMass);  // critically damped: settles in ~0.02 s
  const double expected = kMass * kG / kK;         // 98.1 micrometres
  std::vector<double> sinks;
  for (const double h : {0.002, 0.001, 0.0005}) {
    SCOPED_TRACE("step " + std::to_string(h));
    auto sim = MakeSim(BoxOnPlaneWorld(kK, c, kMass, kSide), {}, OnEngine(engine(), h));
    const int steps = static_cast<int>(std::lround(1.0 / h));
    for (int n = 0; n < steps; ++n) ASSERT_TRUE(sim->Step());
    const double sink = kSide / 2 - sim->engine().ReadBody(0).position.y();
    EXPECT_NEAR(sink, expected, 0.01 * expected);
    sinks.push_back(sink);
    std::printf("step %.4f s: sink %.4f um (m g / k = %.4f um)\n", h, sink * 1e6, expected * 1e6);
  }
  const auto [lo, hi] = std::minmax_element(sinks.begin(), sinks.end());
  EXPECT_LT(*hi - *lo, 0.01 * expected);
}

// The same softness given per step (ODE's ERP/CFM) is another spring at
// another step size: k = ERP / (h CFM). This is what stiffness replaces.
TEST_P(ContactMaterial, PerStepSoftnessSinksDifferentlyAtEachStepSize) {
  const std::string world =
      "<world name=\"Sink\"><surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>"
      "<material name=\"soft\"><softERP>0.1</softERP><softCFM>0.0001</softCFM></material>"
      "<object type=\"Box\" name=\"Box\" material=\"soft\"><mass>10</mass>" +
      Vec("size", 0.5, 0.5, 0.5) + Transform(0, 0.25, 0) + "</object></world>";
  double sink[2];
  const double steps[2] = {0.002, 0.0005};
  for (int i = 0; i < 2; ++i) {
    auto sim = MakeSim(world, {}, OnEngine(engine(), steps[i]));
    for (int n = 0; n < static_cast<int>(std::lround(1.0 / steps[i])); ++n) ASSERT_TRUE(sim->Step());
    sink[i] = 0.25 - sim->engine().ReadBody(0).position.y();
  }
  // Per point k = ERP / (h CFM), four corners: sink = m g h CFM / (4 ERP).
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(sink[i], 10 * kG * steps[i] * 0.0001 / (4 * 0.1), 0.02 * sink[i]);
  EXPECT_GT(sink[0], 3.5 * sink[1]);
}

// Extremes of the sink after a release: the mass-spring-damper's damped
// period and decay, measured from successive deepest points.
struct Ringing {
  double period = 0;         // [s] between the first two deepest points
  double damping_ratio = 0;  // from their excess over the static sink
};

Ringing Release(const std::string& engine, double k, double c, double mass, double side,
                double h) {
  Parameters params = OnEngine(engine, h);
  // ODE limits the speed at which a contact pushes out a penetration; a
  // spring-damper that rings must not meet that limit (docs/contacts.md).
  params.contactMaxCorrectingVel = 1e3;
  auto sim = MakeSim(BoxOnPlaneWorld(k, c, mass, side), {}, params);
  const double rest = mass * kG / k;
  std::vector<double> times, peaks;
  double previous_sink = 0, previous_rate = 0;
  const int steps = static_cast<int>(std::lround(1.2 / h));
  for (int n = 1; n <= steps && peaks.size() < 2; ++n) {
    EXPECT_TRUE(sim->Step());
    const double sink = side / 2 - sim->engine().ReadBody(0).position.y();
    const double rate = sink - previous_sink;
    if (n > 1 && previous_rate > 0 && rate <= 0) {
      times.push_back((n - 1) * h);
      peaks.push_back(previous_sink);
    }
    previous_sink = sink;
    previous_rate = rate;
  }
  Ringing out;
  if (peaks.size() < 2) {
    ADD_FAILURE() << "fewer than two deepest points in 1.2 s";
    return out;
  }
  out.period = times[1] - times[0];
  const double decrement = std::log((peaks[0] - rest) / (peaks[1] - rest));
  out.damping_ratio = decrement / std::sqrt(4 * M_PI * M_PI + decrement * decrement);
  return out;
}

// m = 10 kg, k = 2500 N/m, zeta = 0.1: omega = 15.81 rad/s, damped period
// 2 pi / (omega sqrt(1 - zeta^2)) = 0.3993 s. ODE integrates the contact
// implicitly (backward Euler), which damps by about omega h / 2 more
// (0.008 at 1 ms): the damping ratio is held to within omega h, the period
// to within 1 %.
TEST_P(ContactMaterial, ReleasedBoxRingsLikeItsMassSpringDamper) {
  constexpr double kMass = 10, kK = 2500, kZeta = 0.1;
  const double omega = std::sqrt(kK / kMass);
  const double c = 2 * kZeta * std::sqrt(kK * kMass);  // 31.6 N s/m
  const double period = 2 * M_PI / (omega * std::sqrt(1 - kZeta * kZeta));
  for (const double h : {0.001, 0.0005}) {
    SCOPED_TRACE("step " + std::to_string(h));
    const Ringing r = Release(engine(), kK, c, kMass, 0.5, h);
    EXPECT_NEAR(r.period, period, 0.01 * period);
    EXPECT_NEAR(r.damping_ratio, kZeta, omega * h);
    std::printf("step %.4f s: damped period %.4f s (%.4f), damping ratio %.4f (%.2f)\n", h,
                r.period, period, r.damping_ratio, kZeta);
  }
}

}  // namespace
}  // namespace simpartner::sim
