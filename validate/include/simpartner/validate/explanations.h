// Why a check fails on an engine with the thesis's settings, where that
// engine's documented model says so. One table (explanations.cpp) for the
// report; it never decides a verdict: a check passes or fails on its
// numbers and tolerance alone, the same for every engine, and an
// explanation only shows beside a FAIL. A failure without one is "not yet
// explained".
#pragma once

#include <string>
#include <vector>

namespace simpartner::validate {

struct Explanation {
  std::string experiment;  // its name, e.g. "circle_equal"
  std::string check;       // a part of the checks' labels; "" = every check and the run
  std::string engine;      // "ode", "mujoco"
  std::string why;         // Markdown: the cause, from the engine's documented model
};

// The shipped table.
const std::vector<Explanation>& Explanations();

// The explanation in `table` of a failing check of `experiment` on
// `engine` (label "" for a run that failed); nullptr when there is none.
const Explanation* Explain(const std::vector<Explanation>& table, const std::string& experiment,
                           const std::string& label, const std::string& engine);

// What is wrong with the entries of `table`, one line each naming the
// entry: an unknown experiment or engine, a cause too short to be one.
std::vector<std::string> ExplanationProblems(const std::vector<Explanation>& table);

}  // namespace simpartner::validate
