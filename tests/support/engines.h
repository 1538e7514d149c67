// The physics engines simpartner-sim runs (--engine=ode|mujoco,
// sim_core/include/simpartner/sim/engine.h). A process test about the
// protocol (state, model, commands and replies, run control, determinism,
// hostile input) runs once per engine as a value-parameterized test:
//   class MyTest : public ::testing::TestWithParam<std::string> {...};
//   TEST_P(MyTest, ...) { SimProcess sim(world, url, log, {EngineFlag(GetParam())}); }
//   INSTANTIATE_TEST_SUITE_P(Engines, MyTest, AllEngines(), EngineTestName);
// ctest names the cases Engines/MyTest.<test>/ode and .../mujoco.
#pragma once

#include <gtest/gtest.h>

#include <string>

namespace simpartner::test_support {

inline auto AllEngines() { return ::testing::Values(std::string("ode"), std::string("mujoco")); }

// The case's name suffix: the engine's name.
inline std::string EngineTestName(const ::testing::TestParamInfo<std::string>& info) {
  return info.param;
}

// The sim's flag for `engine`.
inline std::string EngineFlag(const std::string& engine) { return "--engine=" + engine; }

}  // namespace simpartner::test_support
