#include "simpartner/validate/sim_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "simpartner/model/flat_model.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/engine.h"
#include "simpartner/sequencer/check.h"
#include "simpartner/sequencer/sequence.h"

namespace simpartner::validate {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kProgressEverySeconds = 5.0;  // wall time between progress lines

}  // namespace

SimRun::SimRun(const Context& context, const std::string& world)
    : SimRun(context, world, context.params) {}

SimRun::SimRun(const Context& context, const std::string& world, Parameters params)
    : SimRun(context, world, std::move(params), Eigen::Vector3d::Zero()) {}

SimRun::SimRun(const Context& context, const std::string& world,
               const Eigen::Vector3d& move_robots)
    : SimRun(context, world, context.params, move_robots) {}

SimRun::SimRun(const Context& context, const std::string& world, Parameters params,
               const Eigen::Vector3d& move_robots)
    : context_(context), world_name_(world) {
  const std::string path = (fs::path(context.models_dir) / "worlds" / world).string();
  params.environment = path;
  model::World loaded = model::LoadWorldOrThrow(path);
  for (model::RobotInstance& robot : loaded.robots) robot.placement.pretranslate(move_robots);
  Start(std::move(loaded), std::move(params));
}

SimRun::SimRun(const Context& context, const std::string& name, model::World world,
               Parameters params)
    : context_(context), world_name_(name) {
  Start(std::move(world), std::move(params));
}

void SimRun::Start(model::World world, Parameters params) {
  sim_ = std::make_unique<sim::Simulation>(std::move(world), std::move(params), 1);
  for (const model::FlatBody& b : sim_->flat().bodies) com_offsets_.push_back(b.source->com);
}

model::World LoadWorldText(const Context& context, const std::string& name,
                           const std::string& xml) {
  const std::string path = (fs::path(context.models_dir) / "worlds" / name).string();
  model::WorldLoadResult loaded = model::ParseWorld(xml, path);
  if (!loaded.world) throw Error(loaded.diagnostics.Format());
  return std::move(*loaded.world);
}

std::string EngineLacks(const model::World& world, const Parameters& params) {
  const model::FlatModel flat = model::Flatten(world);
  std::string lacks;
  for (const Diagnostic& d : sim::EngineLimits(flat, params))
    lacks += (lacks.empty() ? "" : "; ") + d.message;
  return lacks;
}

int64_t SimRun::StepAt(double t) const { return std::llround(t / dt()); }

double SimRun::SequenceTimes::PhaseStart(const std::string& comment) const {
  for (const auto& [text, start] : phases)
    if (text == comment) return start;
  throw Error("sequence: no comment '" + comment + "'");
}

SimRun::SequenceTimes SimRun::PlaySequence(const std::string& file) {
  const std::string path = (fs::path(context_.models_dir).parent_path() / "sequences" / file).string();
  const sequencer::SequenceParseResult parsed = sequencer::LoadSequenceFile(path);
  if (!parsed.sequence) throw Error(parsed.diagnostics.Format());
  const sequencer::Sequence& sequence = *parsed.sequence;
  if (sequence.segments.size() != 1)
    throw Error(path + ": waits on conditions cannot be replayed in a timed run");
  // The same check and the same command building as simpartner-sequencer's.
  sequencer::Plan plan;
  const DiagnosticList problems =
      sequencer::CheckSequence(sequence, sequencer::ModelFromWorld(sim_->world()), &plan);
  if (!problems.empty()) throw Error(problems.Format());
  const sequencer::Segment& segment = sequence.segments.front();
  SequenceTimes times;
  times.end = segment.end;
  for (const sequencer::PlannedCommand& planned : plan.segments.front().commands) {
    TimedCommand timed;
    timed.step = StepAt(planned.source->time);
    timed.message = planned.message;
    timed.message.request_id = ++request_id_;
    timed.message.sender = "simpartner-validate";
    timed.message.apply_at_step = timed.step;
    timed.origin = path + ":" + std::to_string(planned.source->line);
    queued_.push_back(std::move(timed));
  }
  std::stable_sort(queued_.begin(), queued_.end(),
                   [](const TimedCommand& a, const TimedCommand& b) { return a.step < b.step; });
  for (const sequencer::Note& note : segment.notes) {
    double start = times.end;
    for (const sequencer::Command& c : segment.commands)
      if (c.line > note.line) start = std::min(start, c.time);
    times.phases.emplace_back(note.text, start);
  }
  return times;
}

void SimRun::HandOverDue() {
  // A second of steps ahead: far below the sim's pending-command bound for
  // any file (at most one command per actuator and step), and early enough
  // that every command is queued before its step.
  constexpr int64_t kAheadSteps = 1000;
  while (!queued_.empty() && queued_.front().step <= sim_->step() + kAheadSteps) {
    const TimedCommand& next = queued_.front();
    if (const auto reply = sim_->Submit(next.message))
      throw Error(next.origin + ": " + next.message.target + " at step " +
                  std::to_string(next.step) + " refused by the sim: " + reply->reason);
    queued_.pop_front();
  }
}

void SimRun::RunUntil(double t, const std::function<void()>& each_step) {
  const int64_t last = StepAt(t);
  auto last_report = Clock::now();
  while (sim_->step() < last) {
    HandOverDue();
    const auto step_start = Clock::now();
    const bool stepped = sim_->Step();
    if (context_.step_timing != nullptr) {
      context_.step_timing->steps += 1;
      context_.step_timing->seconds +=
          std::chrono::duration<double>(Clock::now() - step_start).count();
    }
    if (!stepped) {
      std::string reasons;
      for (const warning_t& w : sim_->TakeWarnings())
        reasons += (reasons.empty() ? "" : "; ") + w.source + ": " + w.message;
      throw Error(world_name_ + ": the simulation faulted at t = " + FormatNumber(sim_->time()) +
                  " s: " + reasons);
    }
    if (each_step) each_step();
    // Replies and readings would go on the bus; here only each_step may
    // have taken them.
    sim_->TakeReplies();
    sim_->TakeSensorReadings();
    if ((sim_->step() & 1023) == 0 && context_.progress) {
      const auto now = Clock::now();
      if (std::chrono::duration<double>(now - last_report).count() >= kProgressEverySeconds) {
        last_report = now;
        char text[160];
        std::snprintf(text, sizeof text, "%s: sim time %.1f of %.1f s", world_name_.c_str(),
                      sim_->time(), t);
        context_.progress(text);
      }
    }
  }
  // ODE messages (e.g. "LCP internal error") must not pass silently.
  for (const warning_t& w : sim_->TakeWarnings()) {
    if (w.severity >= warning_t::SEVERITY_WARNING)
      throw Error(world_name_ + ": " + w.source + " warning at step " + std::to_string(w.step) +
                  ": " + w.message);
  }
}

int SimRun::Body(const std::string& name) const {
  const int index = sim_->flat().FindBody("", name);
  if (index < 0) throw Error(world_name_ + ": no body '" + name + "'");
  return index;
}

int SimRun::Joint(const std::string& name) const {
  const int index = sim_->flat().FindJoint("", name);
  if (index < 0) throw Error(world_name_ + ": no joint '" + name + "'");
  return index;
}

int SimRun::Sensor(const std::string& name) const {
  const int index = sim_->flat().FindSensor("", name);
  if (index < 0) throw Error(world_name_ + ": no sensor '" + name + "'");
  return index;
}

sim::BodyReadout SimRun::Read(int body) const { return sim_->engine().ReadBody(body); }

double SimRun::JointPosition(int joint) const { return sim_->engine().JointPosition(joint, 0); }

double SimRun::VerticalContactForce(int body) const {
  return Read(body).contact_force.dot(sim_->world().Up());
}

double SimRun::KineticEnergy() const {
  double energy = 0.0;
  for (size_t i = 0; i < sim_->flat().bodies.size(); ++i) {
    const model::Body& source = *sim_->flat().bodies[i].source;
    if (source.is_static) continue;
    const sim::BodyReadout b = Read(static_cast<int>(i));
    const Eigen::Matrix3d r = b.orientation.toRotationMatrix();
    const Eigen::Vector3d v_com = b.linear_velocity + b.angular_velocity.cross(r * com_offsets_[i]);
    const Eigen::Vector3d w_body = r.transpose() * b.angular_velocity;
    energy += 0.5 * source.mass * v_com.squaredNorm() + 0.5 * w_body.dot(source.inertia * w_body);
  }
  return energy;
}

double SimRun::PotentialEnergy() const {
  double energy = 0.0;
  const Eigen::Vector3d g = sim_->world().gravity;
  for (size_t i = 0; i < sim_->flat().bodies.size(); ++i) {
    const model::Body& source = *sim_->flat().bodies[i].source;
    if (source.is_static) continue;
    const sim::BodyReadout b = Read(static_cast<int>(i));
    const Eigen::Vector3d com = b.position + b.orientation * com_offsets_[i];
    energy -= source.mass * g.dot(com);
  }
  return energy;
}

Eigen::Vector3d SimRun::CentreOfMass(int robot) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double mass = 0.0;
  for (size_t i = 0; i < sim_->flat().bodies.size(); ++i) {
    const model::FlatBody& flat = sim_->flat().bodies[i];
    if (flat.source->is_static || (robot >= 0 && flat.robot != robot)) continue;
    const sim::BodyReadout b = Read(static_cast<int>(i));
    sum += flat.source->mass * (b.position + b.orientation * com_offsets_[i]);
    mass += flat.source->mass;
  }
  return mass > 0 ? Eigen::Vector3d(sum / mass) : sum;
}

}  // namespace simpartner::validate
