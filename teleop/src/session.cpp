#include "simpartner/teleop/session.h"

#include <cmath>
#include <cstdio>
#include <thread>

namespace simpartner::teleop {

Session::Session(SessionOptions options, std::ostream& log)
    : options_(std::move(options)), log_(log), pacer_(options_.period) {
  client::ClientOptions co;
  co.url = options_.url;
  co.program = options_.program;
  co.learn_model = false;
  client_ = std::make_unique<client::Client>(co);
}

Session::~Session() = default;

double Session::Now() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Session::Adopt(const model_t& model) {
  simulation_id_ = model.simulation_id;
  controller_.reset();
  pacer_.Forget();
  if (model.robots.empty()) {
    log_ << "teleop: simulation " << model.simulation_id << " has no robot to drive" << std::endl;
    failed_simulation_id_ = model.simulation_id;
    return;
  }
  robot_model_ = model.robots[0].model;
  const std::string file = options_.mapping_file.empty()
                               ? MappingFileFor(robot_model_, options_.mapping_dir)
                               : options_.mapping_file;
  try {
    Plan plan = BuildPlan(LoadMapping(file), model);
    if (std::isfinite(options_.max_speed))
      plan.drive_scale = std::copysign(options_.max_speed, plan.drive_scale);
    if (plan.steer && std::isfinite(options_.max_steer))
      plan.steer->scale = std::copysign(options_.max_steer, plan.steer->scale);
    log_ << "teleop: simulation " << model.simulation_id << ", robot " << plan.robot << " ("
         << robot_model_ << "), mapping " << file << ": " << plan.wheels.size() << " wheels, "
         << (plan.steer ? "steering, " : "") << plan.levels.size() << " levels" << std::endl;
    controller_ = std::make_unique<Controller>(std::move(plan));
    failed_simulation_id_ = -1;
  } catch (const MappingError& e) {
    log_ << "teleop: cannot drive " << robot_model_ << " of simulation " << model.simulation_id
         << " (the robot stays still):\n" << e.what() << std::endl;
    failed_simulation_id_ = model.simulation_id;
  }
}

void Session::Learn() {
  // Relearn blocks while it waits; not more than a try per half second
  // while no sim answers.
  const double now = Now();
  if (now < next_learn_) return;
  try {
    client_->Relearn(0.3);
    const auto model = client_->model();
    if (model && model->simulation_id != simulation_id_) Adopt(*model);
  } catch (const client::ClientError&) {
    next_learn_ = now + 0.5;  // no sim yet (NoSim): try again
  }
}

void Session::Tick(const InputState& input, bool stopping) {
  if (!client_->catalog() || client_->catalog()->targets().empty() || client_->PendingRestart())
    Learn();
  StopReason safety = StopReason::kNone;
  const auto status = client_->LatestStatus();
  const bool paused = status && status->run_state != status_t::RUN_RUNNING;
  if (stopping)
    safety = StopReason::kSignal;
  else if (client_->SecondsSinceHeard() > (paused ? kSilencePaused : kSilenceRunning))
    safety = StopReason::kSimSilent;
  if (!controller_) {
    demand_ = Demand{};
    demand_.stop = safety == StopReason::kNone ? StopReason::kNoPlan : safety;
    return;
  }
  demand_ = controller_->Update(input, safety);
  const Pacer::Batch batch = pacer_.Due(demand_, Now());
  if (batch.send) Send(batch);
}

void Session::Send(const Pacer::Batch& batch) {
  // Holds only on entering the stop (repeating them would re-latch a
  // drooping pose); joint angles when they change and once a second.
  const std::vector<command_t> commands = CommandsFor(
      controller_->plan(), demand_, batch.full || batch.levels_changed || batch.stop_changed,
      batch.stop_changed);
  try {
    for (const command_t& c : commands) client_->Send(c);
    ++batches_;
  } catch (const client::SimRestarted& e) {
    log_ << "teleop: " << e.what() << "; following the new simulation" << std::endl;
    Learn();
  } catch (const client::ClientError& e) {
    log_ << "teleop: sending failed: " << e.what() << std::endl;
  }
}

void Session::StopAndFlush(const InputState& input) {
  const double until = Now() + 2 * options_.period;
  while (controller_ && Now() < until) {
    demand_ = controller_->Update(input, StopReason::kSignal);
    const Pacer::Batch batch = pacer_.Due(demand_, Now());
    if (batch.send) {
      Send(batch);
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::string Session::StatusLine() const {
  char buffer[256];
  std::string sim = "sim not heard";
  if (const auto status = client_->LatestStatus(); status && client_->SecondsSinceHeard() < 2) {
    const char* state = status->run_state == status_t::RUN_RUNNING  ? "running"
                        : status->run_state == status_t::RUN_PAUSED ? "paused"
                        : status->run_state == status_t::RUN_FAULTED ? "faulted"
                                                                     : "stopped";
    std::snprintf(buffer, sizeof buffer, "sim %s x%.2f t=%.1f s", state, status->real_time_factor,
                  status->sim_time);
    sim = buffer;
  }
  std::snprintf(buffer, sizeof buffer, "%s | %s | wheels %+.2f rad/s | steer %+.2f rad | %s",
                robot_model_.empty() ? "no robot" : robot_model_.c_str(),
                Describe(demand_.stop).c_str(), demand_.moving() ? demand_.wheel_speed : 0.0,
                demand_.steer_angle, sim.c_str());
  std::string line = buffer;
  if (controller_)
    for (size_t k = 0; k < controller_->plan().levels.size(); ++k) {
      std::snprintf(buffer, sizeof buffer, " | %s %+.2f", controller_->plan().levels[k].name.c_str(),
                    controller_->levels()[k]);
      line += buffer;
    }
  return line;
}

}  // namespace simpartner::teleop
