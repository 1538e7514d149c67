// The client's value-count rule (common/command_shape.h) against the sim's
// own parser: for every actuator and sensor of the shipped gen3 and gen4
// worlds, every action and every count from 0 to 12, the client accepts a
// count exactly when the sim does. (The test links sim_core; the client
// library does not.)
#include <gtest/gtest.h>

#include "simpartner/client/catalog.h"
#include "simpartner/client/command.h"
#include "simpartner/client/errors.h"
#include "simpartner/command_shape.h"
#include "simpartner/model/loader.h"
#include "simpartner/parameters.h"
#include "simpartner/sim/simulation.h"

namespace simpartner::client {
namespace {

void CompareWorld(const std::string& world_file) {
  sim::Simulation sim(model::LoadWorldOrThrow(std::string(SP_SOURCE_DIR) + "/models/worlds/" +
                                              world_file),
                      Parameters{}, 1);
  model_t model;
  sim.FillModel(&model);
  const Catalog catalog = Catalog::FromModel(model);
  ASSERT_FALSE(catalog.targets().empty());
  int compared = 0;
  for (const Target& target : catalog.targets()) {
    for (int action = 0; action <= 4; ++action) {
      for (int count = 0; count <= 12; ++count) {
        // Zeros fit every range (forces, velocities, gains, angles and
        // stops inside the joints' limits), so only the count decides;
        // a sensor's rate is its first value and 0 is valid.
        std::vector<double> values(static_cast<size_t>(count), 0.0);
        if (target.is_sensor() && count == 4) values = {0, 11, 0.1, 10};  // a scanner's rays >= 1
        command_t command{};
        command.request_id = 1;
        command.sender = "test";
        command.robot = target.robot;
        command.target = target.name;
        command.action = static_cast<int8_t>(action);
        command.apply_at_step = -1;
        command.values = values;
        command.num_values = count;
        if (target.is_sensor() && target.lcm_kind == sensor_t::KIND_ECHO &&
            action == command_t::ACTION_SET)
          command.text = "echo";
        const auto refusal = sim.Submit(command);
        const std::string client_error = CheckValueCount(target.shape(), action, count);
        const bool sim_accepts = !refusal.has_value();
        const bool client_accepts = client_error.empty();
        // The client is stricter in one place on purpose: a READ carries
        // no values (the sim ignores any).
        if (target.is_sensor() && action == command_t::ACTION_READ && count > 0) {
          EXPECT_FALSE(client_accepts);
          continue;
        }
        EXPECT_EQ(client_accepts, sim_accepts)
            << world_file << ": " << target.qualified_name() << " (" << target.kind_name()
            << ") action " << ActionName(action) << ", " << count << " values: client says '"
            << client_error << "', sim says '" << (refusal ? refusal->reason : "accepted") << "'";
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 100);
}

TEST(CommandShape, SameCountsAsTheSimGen3) { CompareWorld("flat_ground.xml"); }
TEST(CommandShape, SameCountsAsTheSimGen2) { CompareWorld("scanner_wall.xml"); }
TEST(CommandShape, SameCountsAsTheSimGen4) { CompareWorld("gen4_flat.xml"); }

}  // namespace
}  // namespace simpartner::client
