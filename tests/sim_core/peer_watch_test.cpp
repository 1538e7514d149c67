// PeekSimulationId reads the id of SIM_STATE, SIM_STATUS and SIM_MODEL
// without decoding: checked against messages encoded by lcm-gen's code, so
// a reordered .lcm file fails here rather than blinding the sim.
#include <gtest/gtest.h>

#include <vector>

#include "simpartner/channels.h"
#include "simpartner/model_t.hpp"
#include "simpartner/sim/peer_watch.h"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "../support/encode.h"

namespace simpartner::sim {
namespace {

using test_support::Encode;

TEST(PeekSimulationId, ReadsTheIdOfEachKindAsEncoded) {
  constexpr int64_t kId = 0x0123456789abcdefLL;
  state_t state{};
  state.utime = 42;
  state.simulation_id = kId;
  status_t status{};
  status.utime = -1;
  status.simulation_id = kId + 1;
  model_t model{};
  model.utime = 7;
  model.simulation_id = -kId;  // ids are whatever the sim chose; sign included
  const auto s = Encode(state), st = Encode(status), m = Encode(model);
  EXPECT_EQ(PeekSimulationId(channels::kState, s.data(), s.size()), kId);
  EXPECT_EQ(PeekSimulationId(channels::kStatus, st.data(), st.size()), kId + 1);
  EXPECT_EQ(PeekSimulationId(channels::kModel, m.data(), m.size()), -kId);
}

TEST(PeekSimulationId, RefusesWhatIsNotThatChannelsType) {
  state_t state{};
  state.simulation_id = 5;
  const auto s = Encode(state);
  // A state on the status channel: another fingerprint.
  EXPECT_EQ(PeekSimulationId(channels::kStatus, s.data(), s.size()), std::nullopt);
  // Channels that carry no simulation id of a publisher.
  EXPECT_EQ(PeekSimulationId(channels::kCommand, s.data(), s.size()), std::nullopt);
  // Cut short before the end of the id.
  EXPECT_EQ(PeekSimulationId(channels::kState, s.data(), 23), std::nullopt);
  EXPECT_EQ(PeekSimulationId(channels::kState, s.data(), 24), 5);
  EXPECT_EQ(PeekSimulationId(channels::kState, nullptr, 0), std::nullopt);
}

}  // namespace
}  // namespace simpartner::sim
