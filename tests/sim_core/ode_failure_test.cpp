// Beyond the loader's ranges, ODE's own fatal errors: each value that made
// ODE abort the sim (before the loader refused it) is built here directly as
// model structs, bypassing the loader's checks, and must end in an EngineError
// naming ODE's message and the bodies, not in abort(), through the engine
// interface (engine.h) as the sim builds it. Each case runs in a
// child process (gtest's death-test machinery), so that an abort fails the
// test instead of killing the test binary; after the error the child builds
// and steps a healthy world, so a failed world does not break the process.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <ode/ode.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/model/flat_model.h"
#include "simpartner/sim/engine.h"

namespace simpartner::sim {
namespace {

// Ends a death-test child without LeakSanitizer's check at exit: a world
// ODE failed in is abandoned, not freed, on purpose (sim_core/src/ode_world.h), and
// would be reported as a leak under the sanitizers.
[[noreturn]] void ExitChild(int status) {
  std::fflush(stderr);
  std::_Exit(status);
}

model::Body Box(const std::string& name, double mass, const Eigen::Vector3d& size,
                const Eigen::Vector3d& position) {
  model::Body b;
  b.name = name;
  b.geometry.kind = model::GeometryKind::kBox;
  b.geometry.size = size;
  b.mass = mass;
  b.inertia = model::SolidInertia(b.geometry, mass);
  b.pose.translation() = position;
  return b;
}

// A world with the ground plane y = 0 (as the shipped worlds have).
model::World Ground() {
  model::World w;
  w.name = "Crash";
  w.has_plane = true;
  return w;
}

struct CrashCase {
  std::string name;
  std::function<model::World()> world;
  std::string during;  // regex of where ODE fails
};

// gtest prints a case by its name (not as bytes) in test lists and failures.
void PrintTo(const CrashCase& c, std::ostream* out) { *out << c.name; }

std::vector<CrashCase> CrashCases() {
  const Eigen::Vector3d one(1, 1, 1);
  return {
      {"mass_1e308_kg",
       [=] {
         model::World w = Ground();
         w.objects.push_back(Box("Heavy", 1e308, one, {0, 0.5, 0}));
         return w;
       },
       "bSafeNormalize4Fault.* \\(during step\\); bodies: Heavy"},
      {"mass_4_9e_324_kg",
       [=] {
         model::World w = Ground();
         w.objects.push_back(Box("Denormal", 4.9e-324, one, {0, 0.5, 0}));
         return w;
       },
       "during building body 'Denormal'\\); bodies: Denormal"},
      {"mass_1e_12_kg",
       [=] {
         model::World w = Ground();
         w.objects.push_back(Box("Feather", 1e-12, one, {0, 0.5, 0}));
         return w;
       },
       "during step\\); bodies: Feather"},
      {"size_1e_310_m",
       [=] {
         model::World w = Ground();
         model::Body ball;
         ball.name = "Speck";
         ball.geometry.kind = model::GeometryKind::kSphere;
         ball.geometry.size.x() = 1e-310;
         ball.mass = 1.0;
         ball.inertia = model::SolidInertia(ball.geometry, 1.0);
         ball.pose.translation() = Eigen::Vector3d(0, 1, 0);
         w.objects.push_back(ball);
         return w;
       },
       "during building body 'Speck'\\); bodies: Speck"},
      {"size_1e100_m",
       [=] {
         model::World w = Ground();
         w.objects.push_back(Box("Huge", 1, {1, 1e100, 1}, {0, 0.5e100, 0}));
         model::Body b = Box("Block", 1, one, {3, 0.5, 0});
         w.objects.push_back(b);
         model::Joint j;
         j.name = "Link";
         j.kind = model::JointKind::kBall;
         j.body1 = "Huge";
         j.body2 = "Block";
         j.anchor = Eigen::Vector3d(1.5, 0.5, 0);
         w.joints.push_back(j);
         return w;
       },
       "during step"},
      {"placed_1e10_m_away",
       [=] {
         model::World w = Ground();
         w.objects.push_back(Box("Far1", 1, one, {1e10, 0.5, 0}));
         w.objects.push_back(Box("Far2", 1, one, {1e10, 0.5, 3}));
         return w;
       },
       "during collision\\); bodies: Far1, Far2"},
      {"velocity_1e308_m_per_s",
       [=] {
         model::World w = Ground();
         model::Body b = Box("Bullet", 1, one, {0, 0.5, 0});
         b.linear_velocity = Eigen::Vector3d(1e308, 0, 0);
         b.angular_velocity = Eigen::Vector3d(0, 0, 1);
         w.objects.push_back(b);
         return w;
       },
       "bodies: Bullet"},
  };
}

// Runs in the child: builds and steps the case's world until ODE fails;
// exits 0 after an EngineError (and a healthy world stepped afterwards), 3
// when ODE did not fail, 4 on any other exception.
[[noreturn]] void RunCrashCase(const CrashCase& c) {
  const model::World world = c.world();
  const model::FlatModel flat = model::Flatten(world);
  const Parameters params;  // engine=ode, the default
  try {
    std::unique_ptr<PhysicsEngine> ode = MakeEngine(flat, params);
    for (int n = 0; n < 5000; ++n) ode->Step();
    std::fprintf(stderr, "no ODE error in 5000 steps\n");
    ExitChild(3);
  } catch (const EngineError& e) {
    std::fprintf(stderr, "%s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "other exception: %s\n", e.what());
    ExitChild(4);
  }
  // The process goes on: a new world (the sim's reset) steps as usual.
  model::World healthy = Ground();
  healthy.objects.push_back(Box("Cube", 1, {1, 1, 1}, {0, 0.5, 0}));
  const model::FlatModel healthy_flat = model::Flatten(healthy);
  const std::unique_ptr<PhysicsEngine> ode = MakeEngine(healthy_flat, params);
  for (int n = 0; n < 1000; ++n) ode->Step();
  const double y = ode->ReadBody(0).position.y();
  std::fprintf(stderr, "healthy world after: cube at y = %.3f\n", y);
  ExitChild(std::abs(y - 0.5) < 0.01 ? 0 : 5);
}

class OdeFailure : public ::testing::TestWithParam<CrashCase> {};

TEST_P(OdeFailure, IsAnEngineErrorNotAnAbort) {
  const CrashCase& c = GetParam();
  EXPECT_EXIT(RunCrashCase(c), ::testing::ExitedWithCode(0),
              "ODE failed: .*" + c.during + "(.|\n)*healthy world after: cube at y = 0.5");
}

INSTANTIATE_TEST_SUITE_P(ValuesThatAbortedOde, OdeFailure, ::testing::ValuesIn(CrashCases()),
                         [](const ::testing::TestParamInfo<CrashCase>& info) {
                           return info.param.name;
                         });

// A dead world stays dead: a second Step() throws at once instead of
// calling into what ODE left behind. In a child as well.
TEST(OdeFailureDeadWorld, StepAfterAFailureThrowsAgain) {
  EXPECT_EXIT(
      {
        model::World w = Ground();
        w.objects.push_back(Box("Far1", 1, {1, 1, 1}, {1e10, 0.5, 0}));
        w.objects.push_back(Box("Far2", 1, {1, 1, 1}, {1e10, 0.5, 3}));
        const model::FlatModel flat = model::Flatten(w);
        const Parameters params;
        const std::unique_ptr<PhysicsEngine> ode = MakeEngine(flat, params);
        try {
          ode->Step();
        } catch (const EngineError&) {
        }
        if (!ode->dead()) ExitChild(6);
        try {
          ode->Step();
        } catch (const EngineError& e) {
          std::fprintf(stderr, "%s\n", e.what());
          ExitChild(0);
        }
        ExitChild(7);
      },
      ::testing::ExitedWithCode(0), "failed in an earlier step and cannot go on");
}

// ODE keeps its error handlers per process, and another library in the
// process may replace them (ODE's defaults abort()). A world built after
// that still turns ODE's errors into an EngineError: each engine
// reinstalls ours. In a child, as the failed world is abandoned.
TEST(OdeHandlers, AWorldBuiltAfterAnotherLibraryReplacedThemStillThrows) {
  EXPECT_EXIT(
      {
        dSetErrorHandler(nullptr);
        dSetDebugHandler(nullptr);
        dSetMessageHandler(nullptr);
        model::World w = Ground();
        w.objects.push_back(Box("Heavy", 1e308, {1, 1, 1}, {0, 0.5, 0}));
        const model::FlatModel flat = model::Flatten(w);
        const Parameters params;
        try {
          const std::unique_ptr<PhysicsEngine> ode = MakeEngine(flat, params);
          for (int n = 0; n < 5000; ++n) ode->Step();
        } catch (const EngineError& e) {
          std::fprintf(stderr, "%s\n", e.what());
          ExitChild(0);
        }
        ExitChild(3);
      },
      ::testing::ExitedWithCode(0), "ODE failed: .*; bodies: Heavy");
}

}  // namespace
}  // namespace simpartner::sim
