// One run of a shipped world through the sim library, the way
// simpartner-sim runs it: the world file is loaded and validated by the
// loader, commands go through Simulation::Submit (by name, with the step at
// which they apply, as the sequencer sends them) and every step is
// Simulation::Step. Nothing here touches ODE directly.
#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/sim/simulation.h"
#include "simpartner/validate/experiment.h"

namespace simpartner::validate {

// A world an experiment writes itself (the soil rigs), read by the loader
// as if it were the file models_dir/worlds/<name>, so that what it names (a
// soil library) is found as beside a shipped world. Throws
// simpartner::Error with the loader's diagnostics.
model::World LoadWorldText(const Context& context, const std::string& name,
                           const std::string& xml);

// What params.engine cannot represent of `world`, in the engine's words
// ("surface material 'sand' is a soil: the MuJoCo engine does not model
// soil"; several joined by "; "), or "" when it can run it.
std::string EngineLacks(const model::World& world, const Parameters& params);

class SimRun {
 public:
  // world: file name under models_dir/worlds (e.g. "gen1_flat.xml").
  SimRun(const Context& context, const std::string& world, Parameters params);
  SimRun(const Context& context, const std::string& world);
  // The same world with every robot moved by `move_robots` from where the
  // file places it (a run that starts partway along a track).
  SimRun(const Context& context, const std::string& world, const Eigen::Vector3d& move_robots);
  // A world already loaded (LoadWorldText); `name` is for messages.
  SimRun(const Context& context, const std::string& name, model::World world, Parameters params);

  sim::Simulation& sim() { return *sim_; }
  double time() const { return sim_->time(); }
  double dt() const { return sim_->params().stepsize; }
  int64_t StepAt(double t) const;

  // Plays a shipped sequence (sequences/<file>, next to models_dir) as
  // simpartner-sequencer --from-zero sends it: the file is checked against
  // the world's model and its commands are built by the client library
  // (sequencer::CheckSequence), each applied at the step of its time. They
  // are handed to the sim a little ahead of their step while RunUntil runs,
  // as the sequencer streams them, so a file of any length stays within
  // the sim's pending-command bound. The file must be timed only (no
  // waits). Returns the sequence's end [s] and, per <comment>, the time of
  // the first command after it (so that an experiment can find a phase of
  // the sequence by its comment). Throws simpartner::Error with
  // file:line when the file does not fit the world or the sim refuses.
  struct SequenceTimes {
    double end = 0.0;
    std::vector<std::pair<std::string, double>> phases;  // comment text, start [s]
    double PhaseStart(const std::string& comment) const;  // throws simpartner::Error
  };
  SequenceTimes PlaySequence(const std::string& file);

  // Steps until sim time t (to the nearest step), calling each_step after
  // every step, and adds each Simulation::Step's wall time (not
  // each_step's) to the context's step_timing. Throws simpartner::Error
  // with the sim's warnings when the simulation faults (explodes).
  void RunUntil(double t, const std::function<void()>& each_step = {});

  // Lookups that throw simpartner::Error naming the world when absent.
  int Body(const std::string& name) const;
  int Joint(const std::string& name) const;
  int Sensor(const std::string& name) const;

  sim::BodyReadout Read(int body) const;
  Eigen::Vector3d Position(int body) const { return Read(body).position; }
  double JointPosition(int joint) const;
  // Vertical (along up) contact force on a body this step [N].
  double VerticalContactForce(int body) const;
  // Kinetic energy (translation + rotation) of the non-static bodies and
  // their potential energy against the world's gravity [J].
  double KineticEnergy() const;
  double PotentialEnergy() const;
  // Centre of mass of a robot (or all bodies with robot = -1) in the world.
  Eigen::Vector3d CentreOfMass(int robot) const;

 private:
  SimRun(const Context& context, const std::string& world, Parameters params,
         const Eigen::Vector3d& move_robots);
  void Start(model::World world, Parameters params);
  const Context& context_;
  std::string world_name_;
  std::unique_ptr<sim::Simulation> sim_;
  std::vector<Eigen::Vector3d> com_offsets_;  // body frame
  int64_t request_id_ = 0;
  // Commands of the played sequences not yet handed to the sim, in step order.
  struct TimedCommand {
    int64_t step = 0;
    command_t message;
    std::string origin;  // "file:line" for messages
  };
  std::deque<TimedCommand> queued_;
  void HandOverDue();
};

}  // namespace simpartner::validate
