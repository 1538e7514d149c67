// What every case of the message check tests asserts: the message was
// refused, for the field named, by the rule's kind, with a message that
// starts with the field and says what is wrong.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "simpartner/message_problem.h"

namespace simpartner::testing {

inline void ExpectProblem(const MessageCheck& problem, const char* rule, const char* type,
                          const char* field, MessageFault fault, const char* message) {
  ASSERT_TRUE(problem) << rule << ": taken";
  EXPECT_EQ(problem->type, type) << rule;
  EXPECT_EQ(problem->field, field) << rule;
  EXPECT_EQ(problem->fault, fault) << rule;
  EXPECT_EQ(problem->message.rfind(field, 0), 0u) << rule << ": " << problem->message;
  EXPECT_NE(problem->message.find(message), std::string::npos)
      << rule << ": " << problem->message;
}

}  // namespace simpartner::testing
