#include "simpartner/validate/explanations.h"

#include "simpartner/validate/experiment.h"

namespace simpartner::validate {

// An entry cites what it rests on: the engine's header comment
// (sim_core/src/mujoco_world.h), its sources'
// comments, docs/engines.md, docs/contacts.md. Add one only when that
// model explains the figure, and take it out when the engine changes the
// model it rests on (docs/engines.md is the MuJoCo engine's; links are
// relative to docs/validation/, where the report is kept). Taken out so
// far: the thesis-friction circle on
// MuJoCo (2bcdacc put anisotropic friction on Coulomb's ellipse, which
// needs a sideways slip to push across; eff294b made it ODE's box and
// the circle passes).
const std::vector<Explanation>& Explanations() {
  static const std::vector<Explanation> kExplanations = {
      {"circle_equal", "isotropic", "mujoco",
       "Sliding friction applied with a load from a solve without friction "
       "([docs/engines.md](../engines.md#validation-on-both-engines)). Scrubbing wheels slide "
       "and hold in turn. A point that slides gets no friction rows in MuJoCo's solve: a "
       "first solve without them gives its load N, and mu N against the slip is applied "
       "before the solve that counts. ODE solves the load and the friction of every point "
       "together, so on MuJoCo the skid-steer circle's steady state comes out wider."},
      {"circle_differential", "held rim edges", "mujoco",
       "The check's wheel model. It takes each gen1 wheel to stand on its two rim edges, as "
       "ODE's cylinder-plane test puts the points, and splits the wheel's load between them "
       "from its contact torque. MuJoCo's cylinder-plane collider puts its points elsewhere "
       "([docs/engines.md](../engines.md#validation-on-both-engines)), so the split, and "
       "the friction the held edges need, do not describe that run."},
      {"pole_task", "pole speed", "mujoco",
       "One contact point for a cylinder on a box. MuJoCo 2.2's convex collider gives the "
       "pole one point on each cube, so it lies on two points and can roll about the line "
       "through them; ODE's cylinder-box test gives it a line of points. MuJoCo's multi-point "
       "option held the pole but made wheels bounce, and was not kept "
       "([docs/engines.md](../engines.md#validation-on-both-engines))."},
  };
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
