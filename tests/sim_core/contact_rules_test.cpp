// The engine-neutral contact rules (sim_core/src/contact_rules.h) at their
// thresholds, and the same contacts and the same failing world judged the
// same on ODE and on MuJoCo: an engine that carried a copy of its own (a
// threshold of its own, a check of finiteness only) fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "../../sim_core/src/contact_rules.h"
#include "simpartner/model/model.h"
#include "simpartner/text.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::MakeSim;
using testing::Vec;

model::SurfaceProperties Rolling() {
  model::SurfaceProperties s;
  s.friction_direction = model::FrictionDirection::kRolling;
  return s;
}

// ------------------------------------------------------ the rules alone

TEST(ContactRules, ASlipHasADirectionAboveATenthOfAMillimetrePerSecond) {
  EXPECT_FALSE(SlipDirection(Eigen::Vector3d(0.9e-4, 0, 0)));
  const auto direction = SlipDirection(Eigen::Vector3d(0, 0, -1.1e-4));
  ASSERT_TRUE(direction);
  EXPECT_TRUE(direction->isApprox(Eigen::Vector3d(0, 0, -1)));
}

TEST(ContactRules, AWheelRollsAcrossItsAxleUnlessItLiesWithin0_6DegreesOfFlat) {
  const Eigen::Vector3d up(0, 1, 0);
  const auto axle = [](double sine) {
    return Eigen::Vector3d(0, std::sqrt(1 - sine * sine), sine);
  };
  const auto upright = RollingDirection(Rolling(), up, axle(1.0), std::nullopt);
  ASSERT_TRUE(upright);
  EXPECT_TRUE(upright->isApprox(Eigen::Vector3d(1, 0, 0)));
  // sin(0.6 degrees) = 0.0105: 1.1 degrees off flat rolls, 0.3 does not.
  EXPECT_TRUE(RollingDirection(Rolling(), up, std::nullopt, axle(0.02)));
  EXPECT_FALSE(RollingDirection(Rolling(), up, std::nullopt, axle(0.005)));
  // Two wheels, no wheel, or a material that does not ask: none.
  EXPECT_FALSE(RollingDirection(Rolling(), up, axle(1.0), axle(1.0)));
  EXPECT_FALSE(RollingDirection(Rolling(), up, std::nullopt, std::nullopt));
  EXPECT_FALSE(RollingDirection(model::SurfaceProperties{}, up, axle(1.0), std::nullopt));
}

// ------------------------------------------------- the same on both engines

// A free 0.3 m wheel (a cylinder, 0.1 m long: its axis is its spin axis)
// on ground that asks for rolling directions, its axle `sine` of the way
// from the ground's normal (1 = standing on its tread, 0 = lying flat),
// tilted about x and pressed 1 mm into the ground at its lowest point.
std::string WheelWorld(double sine) {
  constexpr double kRadius = 0.3, kLength = 0.1;
  const double cosine = std::sqrt(1 - sine * sine);
  // The cylinder's axis (its z) turned to (0, cosine, sine).
  const double y = kLength / 2 * cosine + kRadius * sine - 0.001;
  const auto n = [](double v) { return ShortestNumber(v); };
  const std::string pose =
      "<transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>"
      "<T10>0</T10><T11>" + n(sine) + "</T11><T12>" + n(cosine) + "</T12><T13>" + n(y) +
      "</T13><T20>0</T20><T21>" + n(-cosine) + "</T21><T22>" + n(sine) +
      "</T22><T23>0</T23></transformation>";
  return "<world name=\"Wheel\"><surface material=\"ground\"><a>0</a><b>1</b><c>0</c><d>0</d>"
         "</surface><material name=\"ground\"><mu>0.3</mu><mu2>0.9</mu2>"
         "<frictionDirection>rolling</frictionDirection></material>"
         "<object type=\"Cylinder\" name=\"Wheel\"><mass>5</mass><radius>0.3</radius>"
         "<length>0.1</length>" + pose + "</object></world>";
}

Parameters OnEngine(const std::string& engine) {
  Parameters params;
  params.engine = engine;
  return params;
}

// The contacts of the wheel's first step on `engine`.
std::vector<ContactReadout> FirstContacts(const std::string& engine, double sine) {
  auto sim = MakeSim(WheelWorld(sine), {}, OnEngine(engine));
  EXPECT_TRUE(sim->Step());
  return sim->engine().ReadContacts();
}

class ContactRulesOnEngine : public ::testing::TestWithParam<std::string> {
 protected:
  const std::string& engine() const { return GetParam(); }
};
INSTANTIATE_TEST_SUITE_P(Engines, ContactRulesOnEngine, ::testing::Values("ode", "mujoco"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

// Rolling across the axle, x here (its sign is free: friction acts along
// a line), from 1.1 degrees off flat to upright.
TEST_P(ContactRulesOnEngine, AWheelOffFlatRollsAcrossItsAxle) {
  for (const double sine : {1.0, 0.02}) {
    SCOPED_TRACE("sine " + ShortestNumber(sine));
    const std::vector<ContactReadout> contacts = FirstContacts(engine(), sine);
    ASSERT_FALSE(contacts.empty());
    for (const ContactReadout& c : contacts)
      EXPECT_NEAR(std::abs(c.rolling_direction.x()), 1.0, 1e-9)
          << "rolling direction " << c.rolling_direction.transpose() << " at "
          << c.position.transpose();
  }
}

// 0.3 degrees off flat: the wheel lies flat and rolls nowhere.
TEST_P(ContactRulesOnEngine, AWheelLyingNearlyFlatHasNoRollingDirection) {
  const std::vector<ContactReadout> contacts = FirstContacts(engine(), 0.005);
  ASSERT_FALSE(contacts.empty());
  for (const ContactReadout& c : contacts)
    EXPECT_EQ(c.rolling_direction, Eigen::Vector3d::Zero())
        << "rolling direction " << c.rolling_direction.transpose() << " at "
        << c.position.transpose();
}

// Ends a death-test child without LeakSanitizer's check at exit: an ODE
// world that failed is abandoned, not freed, on purpose.
[[noreturn]] void ExitChild(int status) {
  std::fflush(stderr);
  std::_Exit(status);
}

model::Body Box(const std::string& name, double mass, const Eigen::Vector3d& position) {
  model::Body b;
  b.name = name;
  b.geometry.kind = model::GeometryKind::kBox;
  b.geometry.size = Eigen::Vector3d(1, 1, 1);
  b.mass = mass;
  b.inertia = model::SolidInertia(b.geometry, mass);
  b.pose.translation() = position;
  return b;
}

// Built past the loader: "Bullet" at 1e308 m/s makes either engine fail
// in its first steps; "Far" stands beyond the loader's coordinates
// (1e6 m), "Heavy" weighs more than its largest mass (1e6 kg), both with
// a finite state; "Fine" is within every range.
model::World FailingWorld() {
  model::World w;
  w.name = "Failing";
  w.has_plane = true;
  model::Body bullet = Box("Bullet", 1, {0, 0.5, 0});
  bullet.linear_velocity = Eigen::Vector3d(1e308, 0, 0);
  w.objects.push_back(bullet);
  w.objects.push_back(Box("Far", 1, {2e6, 0.5, 0}));
  w.objects.push_back(Box("Heavy", 1e7, {3, 0.5, 0}));
  w.objects.push_back(Box("Fine", 1, {-3, 0.5, 0}));
  return w;
}

// The bodies an engine names when it fails are those beyond the loader's
// ranges, by state and by mass, not only those with non-finite numbers.
// The bullet's own state is named where the engine kept it (ODE), not
// where it reset the model to its initial state (MuJoCo). In a child, as
// the failed ODE world is abandoned.
TEST_P(ContactRulesOnEngine, AFailedEngineNamesTheBodiesBeyondTheRangesByStateAndMass) {
  EXPECT_EXIT(
      {
        const model::World world = FailingWorld();
        const model::FlatModel flat = model::Flatten(world);
        const Parameters params = OnEngine(engine());
        try {
          const std::unique_ptr<PhysicsEngine> physics = MakeEngine(flat, params);
          for (int n = 0; n < 100; ++n) physics->Step();
        } catch (const EngineError& e) {
          std::fprintf(stderr, "%s\n", e.what());
          ExitChild(0);
        }
        std::fprintf(stderr, "no failure in 100 steps\n");
        ExitChild(3);
      },
      ::testing::ExitedWithCode(0), "failed: .*; bodies: (Bullet, )?Far, Heavy\n");
}

}  // namespace
}  // namespace simpartner::sim
