// Every rule of CheckState (message_checks.h), one case each: alone, and
// against the outline of its model.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <vector>

#include "../support/non_finite.h"
#include "expect_problem.h"
#include "simpartner/message_checks.h"

namespace simpartner {
namespace {

using test_support::kInf;
using test_support::kNaN;

ModelOutline TwoBodiesOneJoint() {
  ModelOutline outline;
  outline.simulation_id = 5;
  outline.bodies = 2;
  outline.joints = 1;
  return outline;
}

// Two bodies at rest with unit orientations, one joint, one wheel on soil.
state_t GoodState() {
  state_t s{};
  s.simulation_id = 5;
  s.step = 10;
  s.sim_time = 0.01;
  s.bodies.resize(2);
  for (body_state_t& b : s.bodies) b.orientation[0] = 1;
  s.num_bodies = 2;
  s.joints.resize(1);
  s.num_joints = 1;
  s.wheel_soil.resize(1);
  s.wheel_soil[0].body = 1;
  s.num_wheel_soil = 1;
  return s;
}

struct StateCase {
  const char* rule;
  std::function<void(state_t*)> damage;
  const char* field;
  const char* message;
  MessageFault fault;
};

TEST(CheckState, TakesAGoodStateWithAndWithoutItsModel) {
  const ModelOutline model = TwoBodiesOneJoint();
  EXPECT_FALSE(CheckState(GoodState(), nullptr));
  EXPECT_FALSE(CheckState(GoodState(), &model));
}

TEST(CheckState, RefusesEachBrokenRuleNamingTheField) {
  using F = MessageFault;
  const std::vector<StateCase> cases = {
      {"step not negative", [](state_t* s) { s->step = -1; }, "step", "step = -1 (negative)",
       F::kOutOfRange},
      {"sim_time finite", [](state_t* s) { s->sim_time = kNaN; }, "sim_time", "sim_time = nan",
       F::kNonFinite},
      {"body position finite", [](state_t* s) { s->bodies[1].position[2] = kNaN; },
       "bodies[1].position[2]", "bodies[1].position[2] = nan", F::kNonFinite},
      {"body contact_force finite", [](state_t* s) { s->bodies[0].contact_force[0] = kInf; },
       "bodies[0].contact_force[0]", "bodies[0].contact_force[0] = inf", F::kNonFinite},
      {"body contact_torque finite", [](state_t* s) { s->bodies[0].contact_torque[1] = kNaN; },
       "bodies[0].contact_torque[1]", "bodies[0].contact_torque[1] = nan", F::kNonFinite},
      {"body orientation finite", [](state_t* s) { s->bodies[0].orientation[1] = kInf; },
       "bodies[0].orientation[1]", "bodies[0].orientation[1] = inf", F::kNonFinite},
      {"body orientation unit", [](state_t* s) { s->bodies[0].orientation[0] = 0; },
       "bodies[0].orientation",
       "bodies[0].orientation has length 0 (a unit quaternion is needed)", F::kNotUnit},
      {"joint position finite", [](state_t* s) { s->joints[0].position[0] = kNaN; },
       "joints[0].position[0]", "joints[0].position[0] = nan", F::kNonFinite},
      {"joint rate finite", [](state_t* s) { s->joints[0].rate[1] = kNaN; }, "joints[0].rate[1]",
       "joints[0].rate[1] = nan", F::kNonFinite},
      {"joint anchor finite", [](state_t* s) { s->joints[0].anchor[2] = kInf; },
       "joints[0].anchor[2]", "joints[0].anchor[2] = inf", F::kNonFinite},
      {"joint force1 finite", [](state_t* s) { s->joints[0].force1[1] = kNaN; },
       "joints[0].force1[1]", "joints[0].force1[1] = nan", F::kNonFinite},
      {"joint torque1 finite", [](state_t* s) { s->joints[0].torque1[0] = kNaN; },
       "joints[0].torque1[0]", "joints[0].torque1[0] = nan", F::kNonFinite},
      {"wheel figures finite", [](state_t* s) { s->wheel_soil[0].slip = kNaN; },
       "wheel_soil[0].slip", "wheel_soil[0].slip = nan", F::kNonFinite},
      {"wheel normal_force finite", [](state_t* s) { s->wheel_soil[0].normal_force[2] = kInf; },
       "wheel_soil[0].normal_force[2]", "wheel_soil[0].normal_force[2] = inf", F::kNonFinite},
      {"wheel shear_force finite", [](state_t* s) { s->wheel_soil[0].shear_force[0] = kNaN; },
       "wheel_soil[0].shear_force[0]", "wheel_soil[0].shear_force[0] = nan", F::kNonFinite},
  };
  for (const StateCase& c : cases) {
    state_t s = GoodState();
    c.damage(&s);
    testing::ExpectProblem(CheckState(s, nullptr), c.rule, "state_t", c.field, c.fault,
                           c.message);
  }
}

TEST(CheckState, RefusesWhatDoesNotFitItsModel) {
  using F = MessageFault;
  const std::vector<StateCase> cases = {
      {"as many bodies as the model",
       [](state_t* s) {
         s->bodies.resize(3);
         s->bodies[2].orientation[0] = 1;
         s->num_bodies = 3;
       },
       "num_bodies", "num_bodies = 3 but the model of simulation 5 has 2", F::kCountMismatch},
      {"as many joints as the model",
       [](state_t* s) {
         s->joints.clear();
         s->num_joints = 0;
       },
       "num_joints", "num_joints = 0 but the model of simulation 5 has 1", F::kCountMismatch},
      {"each wheel a body of the model", [](state_t* s) { s->wheel_soil[0].body = 2; },
       "wheel_soil[0].body", "wheel_soil[0].body = 2 but the model of simulation 5 has 2 bodies",
       F::kBadIndex},
  };
  const ModelOutline model = TwoBodiesOneJoint();
  for (const StateCase& c : cases) {
    state_t s = GoodState();
    c.damage(&s);
    EXPECT_FALSE(CheckState(s, nullptr)) << c.rule << ": the structure alone is fine";
    testing::ExpectProblem(CheckState(s, &model), c.rule, "state_t", c.field, c.fault,
                           c.message);
  }
}

TEST(CheckState, NamesTheBodyElementForCallersThatLabelIt) {
  state_t s = GoodState();
  s.bodies[1].position[0] = kNaN;
  const MessageCheck problem = CheckState(s, nullptr);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->array, "bodies");
  EXPECT_EQ(problem->index, 1);
  EXPECT_EQ(problem->Format(), "state_t.bodies[1].position[0] = nan");
}

}  // namespace
}  // namespace simpartner
