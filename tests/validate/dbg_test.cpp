#include <gtest/gtest.h>
#include "simpartner/validate/sim_run.h"
#include "simpartner/validate/experiment.h"
namespace simpartner::validate { namespace {
TEST(Dbg, Circle) {
  Context context; context.models_dir = SP_SOURCE_DIR "/models";
  context.params.engine = getenv("ENG") ? getenv("ENG") : "mujoco"; context.params.contactMu = 1.0;
  SimRun run(context, "gen1_flat.xml", context.params);
  run.PlaySequence("gen1_circle_equal_speeds.xml");
  int n = 0;
  run.RunUntil(8.0, [&] {
    ++n; if (run.time() < 1.995 || run.time() > 2.3 || n % 10) return;
    for (size_t b = 0; b < run.sim().flat().bodies.size(); ++b) {
      const auto& fb = run.sim().flat().bodies[b];
      if (fb.name.find("Wheel") == std::string::npos && true) continue;
      auto r = run.sim().engine().ReadBody(b);
      printf("t %.2f %-12s p %.3f %.3f %.3f v %.3f %.3f %.3f fy %.1f w %.2f %.2f %.2f\n", run.time(), fb.name.c_str(), r.position.x(), r.position.y(), r.position.z(), r.linear_velocity.x(), r.linear_velocity.y(), r.linear_velocity.z(), r.contact_force.y(), r.angular_velocity.x(), r.angular_velocity.y(), r.angular_velocity.z());
    }
  });
}
}}
