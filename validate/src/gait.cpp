#include "simpartner/validate/gait.h"

#include <algorithm>
#include <cmath>

#include "simpartner/diagnostic.h"
#include "simpartner/text.h"
#include "simpartner/validate/experiment.h"
#include "simpartner/validate/sim_run.h"

namespace simpartner::validate {
namespace {

// The gait's bodies in the run.
struct GaitBodies {
  int chassis = -1;
  std::array<int, kGaitWheels> wheel{}, calf{};
  explicit GaitBodies(const SimRun& run) : chassis(run.Body("RearChassis")) {
    for (int i = 0; i < kGaitWheels; ++i) {
      wheel[i] = run.Body("Wheel" + std::to_string(i + 1));
      calf[i] = run.Body("Calf" + std::to_string(i + 1));
    }
  }
};

// Adds each step to the phase it lies in, for the cycles after the first.
class PhaseMeter {
 public:
  PhaseMeter(const GaitSequence& gait, SimRun& run)
      : gait_(gait), bodies_(run), up_(run.sim().world().Up()) {
    for (const GaitPhase& p : gait.phases) out_.push_back(PhaseSlip{p, 0.0, {}});
  }

  void Step(const SimRun& run) {
    const int phase = PhaseOf(run.time() - 0.5 * run.dt());
    if (phase < 0) return;
    const sim::BodyReadout chassis = run.Read(bodies_.chassis);
    Eigen::Vector3d forward = chassis.orientation * Eigen::Vector3d::UnitX();
    forward = (forward - forward.dot(up_) * up_).normalized();
    if (phase != current_) StartPhase(run, phase, forward);
    const double dt = run.dt();
    PhaseSlip& out = out_[phase];
    for (int i = 0; i < kGaitWheels; ++i) {
      const sim::BodyReadout wheel = run.Read(bodies_.wheel[i]);
      const sim::BodyReadout calf = run.Read(bodies_.calf[i]);
      // The contact point r below the centre: v_contact = v + w x (-r up).
      const double rolling = kWheelRadius * wheel.angular_velocity.cross(up_).dot(forward);
      const double sliding = wheel.linear_velocity.dot(forward) - rolling;
      WheelInPhase& w = out.wheels[i];
      w.rolled += rolling * dt;
      w.slid += sliding * dt;
      w.calf_rolled += kWheelRadius * calf.angular_velocity.cross(up_).dot(forward) * dt;
      w.friction += wheel.contact_force.dot(forward) * dt;
      w.load += wheel.contact_force.dot(up_) * dt;
    }
  }

  // Closes the last phase; the sums per cycle, forces as means over the phase.
  std::vector<PhaseSlip> Result(const SimRun& run) {
    if (current_ >= 0) EndPhase(run);
    const double cycles = std::max(1, cycles_seen_);
    for (PhaseSlip& p : out_) {
      p.body_moved /= cycles;
      for (WheelInPhase& w : p.wheels) {
        w.moved /= cycles;
        w.rolled /= cycles;
        w.slid /= cycles;
        w.calf_rolled /= cycles;
        w.friction /= cycles * p.phase.duration;
        w.load /= cycles * p.phase.duration;
      }
    }
    return out_;
  }

 private:
  // The phase of time t, or -1 before the second cycle.
  int PhaseOf(double t) const {
    const double cycle_time = gait_.CycleTime();
    const double since = t - kGaitStart - cycle_time;
    if (since < 0.0) return -1;
    double in_cycle = std::fmod(since, cycle_time);
    for (size_t i = 0; i < gait_.phases.size(); ++i) {
      if (in_cycle < gait_.phases[i].duration) return static_cast<int>(i);
      in_cycle -= gait_.phases[i].duration;
    }
    return static_cast<int>(gait_.phases.size()) - 1;
  }

  // Positions at the start of the step that begins the phase: the end of
  // the previous step, i.e. now minus this step's motion.
  void StartPhase(const SimRun& run, int phase, const Eigen::Vector3d& forward) {
    if (current_ >= 0) EndPhase(run);
    if (phase == 0) ++cycles_seen_;
    current_ = phase;
    forward_ = forward;
    const double dt = run.dt();
    const sim::BodyReadout chassis = run.Read(bodies_.chassis);
    chassis_start_ = (chassis.position - chassis.linear_velocity * dt).dot(forward);
    for (int i = 0; i < kGaitWheels; ++i) {
      const sim::BodyReadout wheel = run.Read(bodies_.wheel[i]);
      wheel_start_[i] = (wheel.position - wheel.linear_velocity * dt).dot(forward);
    }
  }

  void EndPhase(const SimRun& run) {
    PhaseSlip& out = out_[current_];
    out.body_moved += run.Position(bodies_.chassis).dot(forward_) - chassis_start_;
    for (int i = 0; i < kGaitWheels; ++i)
      out.wheels[i].moved += run.Position(bodies_.wheel[i]).dot(forward_) - wheel_start_[i];
  }

  const GaitSequence& gait_;
  GaitBodies bodies_;
  Eigen::Vector3d up_;
  std::vector<PhaseSlip> out_;
  int current_ = -1;
  int cycles_seen_ = 0;
  Eigen::Vector3d forward_ = Eigen::Vector3d::UnitX();
  double chassis_start_ = 0.0;
  std::array<double, kGaitWheels> wheel_start_{};
};

}  // namespace

double GaitSequence::CycleTime() const {
  double total = 0.0;
  for (const GaitPhase& p : phases) total += p.duration;
  return total;
}

double CalfPitch(bool front, double foot) {
  // workpartner_gen1_light.xml: thigh and calf 0.3 m, the hips 0.48 m above
  // the axles; the front knees bend back, the rear ones forward.
  constexpr double kLink = 0.3, kHipHeight = 0.48;
  const double reach = std::hypot(foot, kHipHeight);
  const double knee_half_angle = std::acos(reach / (2.0 * kLink));
  const double hip_to_foot = std::atan2(-kHipHeight, foot);
  return front ? hip_to_foot + knee_half_angle : hip_to_foot - knee_half_angle;
}

double HeldWheelRoll(bool front, double foot_from, double foot_to) {
  return kWheelRadius * (CalfPitch(front, foot_from) - CalfPitch(front, foot_to));
}

GaitSequence CaterpillarSequence() {
  return {"gen1_light_caterpillar.xml", 6,
          {{1.5, "front feet reach", {true, true, false, false}},
           {3.5, "push", {false, false, true, true}}},
          0.25};
}

GaitSequence RollingWalkingSequence() {
  return {"gen1_light_rolking.xml", 5,
          {{1.0, "leg 1 steps", {true, false, false, false}},
           {1.0, "leg 3 steps", {false, false, true, false}},
           {1.0, "leg 2 steps", {false, true, false, false}},
           {1.0, "leg 4 steps", {false, false, false, true}},
           {3.0, "push", {false, false, false, false}}},
          0.25};
}

GaitRun RunGait(const Context& context, const GaitSequence& gait) {
  SimRun run(context, "slippery_ground.xml");
  const int chassis = run.Body("RearChassis");
  const double cycle_time = gait.CycleTime();
  const double file_end = kGaitStart + gait.cycles * cycle_time;
  const SimRun::SequenceTimes times = run.PlaySequence(gait.file);
  // The speed is measured over whole cycles: a file that does not last
  // them would measure something else.
  if (std::abs(times.end - file_end) > 0.5 * run.dt())
    throw Error(gait.file + " lasts " + FormatNumber(times.end) + " s, not the " + FormatNumber(file_end) +
                " s of " + std::to_string(gait.cycles) + " cycles of " + FormatNumber(cycle_time) +
                " s");
  // The unit tests play the first three cycles of the same file.
  const int cycles = context.quick ? std::min(3, gait.cycles) : gait.cycles;
  const double end = kGaitStart + cycles * cycle_time;
  GaitRun out;
  out.x.title = "rear chassis x";
  double x_after_first = 0.0;
  PhaseMeter meter(gait, run);
  run.RunUntil(end, [&] {
    const double t = run.time();
    if (std::abs(t - (kGaitStart + cycle_time)) < 0.5 * run.dt())
      x_after_first = run.Position(chassis).x();
    meter.Step(run);
    if (run.sim().step() % 10 == 0) {
      out.x.x.push_back(t);
      out.x.y.push_back(run.Position(chassis).x());
    }
  });
  out.sim_seconds = run.time();
  out.speed = (run.Position(chassis).x() - x_after_first) / ((cycles - 1) * cycle_time);
  out.cycles = cycles;
  out.phases = meter.Result(run);
  return out;
}

std::string PhaseSlipTable(const std::vector<PhaseSlip>& phases, double mu) {
  auto cm = [](double m) { return FormatFixed(m * 100.0, 2); };
  std::string table =
      "| phase | body moved [cm] | wheel | held | moved [cm] | rolled [cm] (calf's turn) | "
      "slid [cm] | friction [N] | mu x load [N] |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  for (const PhaseSlip& p : phases) {
    for (int i = 0; i < kGaitWheels; ++i) {
      const WheelInPhase& w = p.wheels[i];
      table += "| " + (i == 0 ? p.phase.what + " (" + FormatNumber(p.phase.duration) + " s)" : "") +
               " | " + (i == 0 ? cm(p.body_moved) : "") + " | " + std::to_string(i + 1) + " | " +
               (p.phase.driven[i] ? "no" : "yes") + " | " + cm(w.moved) + " | " + cm(w.rolled) +
               " (" + cm(w.calf_rolled) + ") | " + cm(w.slid) + " | " + FormatFixed(w.friction, 2) +
               " | " + FormatFixed(mu * w.load, 2) + " |\n";
    }
  }
  return table;
}

}  // namespace simpartner::validate
