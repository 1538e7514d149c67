// An OdeError inside a step (ode_failure_test.cpp shows ODE's aborts become
// one) pauses the Simulation like an exploding state: Step() returns
// false, the sim is faulted, and the warning names ODE's message and the
// body, with severity error. Run in a child, as ODE is left mid-step.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "simpartner/model/model.h"
#include "simpartner/sim/simulation.h"

namespace simpartner::sim {
namespace {

// Ends a death-test child without LeakSanitizer's check at exit: a world
// ODE failed in is abandoned, not freed, on purpose (ode_world.h), and
// would be reported as a leak under the sanitizers.
[[noreturn]] void ExitChild(int status) {
  std::fflush(stderr);
  std::_Exit(status);
}

// A 1e308 kg box on the ground: past the loader's range, and ODE fails in
// its first steps ('!bSafeNormalize4Fault').
model::World HeavyBoxWorld() {
  model::World w;
  w.name = "HeavyBox";
  w.has_plane = true;
  w.plane = Eigen::Vector4d(0, 1, 0, 0);
  w.gravity = Eigen::Vector3d(0, -9.81, 0);
  model::Body b;
  b.name = "Heavy";
  b.geometry.kind = model::GeometryKind::kBox;
  b.geometry.size = Eigen::Vector3d(1, 1, 1);
  b.mass = 1e308;
  b.inertia = model::SolidInertia(b.geometry, b.mass);
  b.pose.translation() = Eigen::Vector3d(0, 0.5, 0);
  w.objects.push_back(b);
  return w;
}

TEST(OdeFailurePause, AnOdeErrorPausesTheSimAndNamesTheBody) {
  EXPECT_EXIT(
      {
        Simulation sim(HeavyBoxWorld(), Parameters(), 1);
        int steps = 0;
        while (steps < 5000 && sim.Step()) ++steps;
        if (!sim.faulted()) ExitChild(3);
        if (sim.Step()) ExitChild(4);  // stays paused
        for (const warning_t& w : sim.TakeWarnings()) {
          if (w.source != "ode" || w.severity != warning_t::SEVERITY_ERROR) continue;
          std::fprintf(stderr, "%s | bodies: %s\n", w.message.c_str(),
                       w.bodies.empty() ? "" : w.bodies[0].c_str());
          ExitChild(0);
        }
        ExitChild(5);
      },
      ::testing::ExitedWithCode(0),
      "ODE failed: .*; the sim is paused: reset to go on \\| bodies: Heavy");
}

}  // namespace
}  // namespace simpartner::sim
