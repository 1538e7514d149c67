#include "simpartner/validate/explanations.h"

#include "simpartner/validate/experiment.h"

namespace simpartner::validate {

// An entry cites what it rests on: the engine's header comment
// (sim_core/include/simpartner/sim/mujoco_world.h), its sources'
// comments, docs/engines.md, docs/contacts.md. Add one only when that
// model explains the figure, and take it out when the engine changes the
// model it rests on. Taken out so far: the thesis-friction circle on
// MuJoCo (2bcdacc put anisotropic friction on Coulomb's ellipse, which
// needs a sideways slip to push across; eff294b made it ODE's box and
// the circle passes).
const std::vector<Explanation>& Explanations() {
  static const std::vector<Explanation> kExplanations = {};
  return kExplanations;
}

const Explanation* Explain(const std::vector<Explanation>& table, const std::string& experiment,
                           const std::string& label, const std::string& engine) {
  for (const Explanation& e : table)
    if (e.experiment == experiment && e.engine == engine &&
        label.find(e.check) != std::string::npos)
      return &e;
  return nullptr;
}

std::vector<std::string> ExplanationProblems(const std::vector<Explanation>& table) {
  constexpr size_t kShortestCause = 40;  // characters: a sentence that names a mechanism
  std::vector<std::string> problems;
  for (const Explanation& e : table) {
    const std::string entry = e.experiment + " / '" + e.check + "' / " + e.engine + ": ";
    if (FindExperiment(e.experiment) == nullptr) problems.push_back(entry + "no such experiment");
    if (e.engine != "ode" && e.engine != "mujoco") problems.push_back(entry + "no such engine");
    if (e.why.size() < kShortestCause)
      problems.push_back(entry + "the cause '" + e.why + "' is too short to be one");
  }
  return problems;
}

}  // namespace simpartner::validate
