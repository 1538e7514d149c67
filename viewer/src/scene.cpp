#include "simpartner/viewer/scene.h"
#include "simpartner/text.h"

#include <cmath>
#include <sstream>

namespace simpartner::viewer {
namespace {

constexpr size_t kMaxRecentProblems = 8;

Eigen::Quaterniond Quat(const double q[4]) { return Eigen::Quaterniond(q[0], q[1], q[2], q[3]); }

// Radius of a sphere about the body frame origin that holds the geometry.
double BoundingRadius(const geometry_t& g) {
  switch (g.kind) {
    case geometry_t::KIND_BOX:
      return 0.5 * Eigen::Vector3d(g.size[0], g.size[1], g.size[2]).norm();
    case geometry_t::KIND_SPHERE: return g.size[0];
    case geometry_t::KIND_CYLINDER: return std::hypot(g.size[0], g.size[1] / 2);
    case geometry_t::KIND_CAPSULE: return g.size[0] + g.size[1] / 2;
    default: return 0.05;
  }
}

// Which element of the model a problem is in, as the viewer names it:
// " (body 'Arm'" (the caller adds to it and closes it), or "" for a field
// of no body or joint.
std::string ElementLabel(const MessageProblem& problem, const model_t& model) {
  const auto in = [&](const auto& elements, const char* word) -> std::string {
    if (problem.index < 0 || static_cast<size_t>(problem.index) >= elements.size()) return "";
    return std::string(" (") + word + " '" + elements[static_cast<size_t>(problem.index)].name + "'";
  };
  if (problem.array == "bodies") return in(model.bodies, "body");
  if (problem.array == "joints") return in(model.joints, "joint");
  return "";
}

// The viewer's count of a state's problem (its HUD and summary line).
Rejection StateRejection(const MessageProblem& problem) {
  switch (problem.fault) {
    case MessageFault::kCountMismatch:
      return problem.field == "num_joints" ? Rejection::kJointCount : Rejection::kBodyCount;
    case MessageFault::kNotUnit: return Rejection::kBadQuaternion;
    case MessageFault::kNonFinite: return Rejection::kNonFinite;
    default: return Rejection::kBadState;
  }
}

}  // namespace

const char* RejectionName(Rejection r) {
  switch (r) {
    case Rejection::kUndecodable: return "undecodable";
    case Rejection::kOtherSimulation: return "other simulation";
    case Rejection::kBodyCount: return "body count";
    case Rejection::kJointCount: return "joint count";
    case Rejection::kNonFinite: return "non-finite";
    case Rejection::kBadQuaternion: return "bad quaternion";
    case Rejection::kBadModel: return "bad model";
    case Rejection::kBadReading: return "bad reading";
    case Rejection::kBadRuts: return "bad ruts";
    case Rejection::kBadState: return "bad state";
  }
  return "?";
}

Verdict Scene::Reject(Rejection kind, const std::string& channel, const std::string& message) {
  ++rejected_[static_cast<int>(kind)];
  ++version_;
  Problem problem{kind, channel, channel + ": " + message};
  recent_problems_.push_back(problem);
  while (recent_problems_.size() > kMaxRecentProblems) recent_problems_.pop_front();
  Verdict v;
  v.problem = std::move(problem);
  return v;
}

void Scene::CountUndecodable(const std::string& channel, const std::string& refusal) {
  Reject(Rejection::kUndecodable, channel, refusal + "; ignored");
}

int64_t Scene::rejected_total() const {
  int64_t total = 0;
  for (int64_t n : rejected_) total += n;
  return total;
}

std::string Scene::RejectionSummary() const {
  std::string out;
  for (int k = 0; k < kRejectionKinds; ++k) {
    if (rejected_[static_cast<size_t>(k)] == 0) continue;
    if (!out.empty()) out += ", ";
    out += std::to_string(rejected_[static_cast<size_t>(k)]) + " " +
           RejectionName(static_cast<Rejection>(k));
  }
  return out;
}

Verdict Scene::OfferModel(const model_t& model) {
  if (auto problem = CheckModel(model)) {
    const std::string label = ElementLabel(*problem, model);
    return Reject(Rejection::kBadModel, "SIM_MODEL",
                  problem->message + (label.empty() ? "" : label + ")") + " (simulation " +
                      std::to_string(model.simulation_id) + "): model ignored");
  }
  // Another simulation's model (a second sim on the bus, a stale or forged
  // one) does not replace the one shown (simulation_follower.h).
  if (follower_.OnModel(model.simulation_id, SimulationFollower::Clock::now()) ==
      SimulationFollower::Verdict::kOther)
    return Reject(Rejection::kOtherSimulation, "SIM_MODEL",
                  "simulation " + std::to_string(model.simulation_id) + " from '" + model.sender +
                      "' while simulation " + std::to_string(follower_.followed()) +
                      " is shown (another sim on this bus, or a stale or forged model): ignored");
  Verdict v;
  v.accepted = true;
  ++version_;
  if (model_ && model_->simulation_id == model.simulation_id) {
    // The periodic re-announcement: sensor settings may have changed.
    model_->sensors = model.sensors;
    model_->num_sensors = model.num_sensors;
    outline_ = OutlineOf(*model_);
    return v;
  }
  model_ = model;
  outline_ = OutlineOf(model);
  ++model_generation_;
  state_.reset();
  status_.reset();
  scans_.clear();
  for (RutMap& ruts : ruts_) ruts.Clear();
  return v;
}

Verdict Scene::OfferSoilRuts(const soil_ruts_t& ruts) {
  follower_.Heard(ruts.simulation_id, SimulationFollower::Clock::now());
  if (!model_) {
    Verdict v;
    v.want_model = true;  // the model's answer brings the ruts again
    return v;
  }
  if (ruts.simulation_id != model_->simulation_id)
    return Reject(Rejection::kOtherSimulation, "SIM_SOIL_RUTS",
                  "simulation_id = " + std::to_string(ruts.simulation_id) + ", the model is of " +
                      std::to_string(model_->simulation_id) + ": ignored");
  std::optional<std::string> problem;
  if (auto bad = CheckSoilRuts(ruts)) problem = bad->message;
  if (!problem) problem = CheckRutsGround(ruts, *model_, Up());
  if (problem)
    return Reject(Rejection::kBadRuts, "SIM_SOIL_RUTS",
                  *problem + " (step " + std::to_string(ruts.step) + "): ignored");
  ++version_;
  if (!ruts_[ruts.ground == soil_ruts_t::GROUND_HEIGHTFIELD ? 1 : 0].Take(ruts))
    return Reject(Rejection::kBadRuts, "SIM_SOIL_RUTS",
                  "more than " + std::to_string(RutMap::kMaxCells) +
                      " rut cells: the newest are not shown");
  Verdict v;
  v.accepted = true;
  return v;
}

Verdict Scene::OfferState(state_t&& s) {
  follower_.Heard(s.simulation_id, SimulationFollower::Clock::now());
  if (!model_) {
    ++states_before_model_;
    Verdict v;
    v.want_model = true;
    return v;
  }
  const model_t& m = *model_;
  if (s.simulation_id != m.simulation_id) {
    Verdict v = Reject(Rejection::kOtherSimulation, "SIM_STATE",
                       "simulation_id = " + std::to_string(s.simulation_id) + ", the model is of " +
                           std::to_string(m.simulation_id) + ": ignored, asking for the model");
    v.want_model = !follower_.IsOther(s.simulation_id);  // its model came and was not taken
    return v;
  }
  if (auto problem = CheckState(s, &outline_)) {
    const std::string label = ElementLabel(*problem, m);
    return Reject(StateRejection(*problem), "SIM_STATE",
                  problem->message + (label.empty() ? " (step " : label + ", step ") +
                      std::to_string(s.step) + "): ignored");
  }
  state_ = std::move(s);
  ++states_accepted_;
  ++version_;
  Verdict v;
  v.accepted = true;
  return v;
}

Verdict Scene::OfferStatus(const status_t& status) {
  Verdict v;
  if (auto problem = CheckStatus(status))
    return Reject(Rejection::kNonFinite, "SIM_STATUS", problem->message + ": ignored");
  v.accepted = true;
  follower_.Heard(status.simulation_id, SimulationFollower::Clock::now());
  if (EndsSimulation(status.run_state)) follower_.Ended(status.simulation_id);
  // A status of another simulation means the sim restarted (or a paused
  // one is running that we have not heard the model of), unless its model
  // came and was not taken.
  v.want_model = (!model_ || status.simulation_id != model_->simulation_id) &&
                 !follower_.IsOther(status.simulation_id);
  if (!v.want_model || !model_) {
    status_ = status;
    ++version_;
  }
  return v;
}

Verdict Scene::OfferSensorReading(const sensor_reading_t& r) {
  Verdict v;
  if (!model_ || r.simulation_id != model_->simulation_id) {
    // Not counted: readings of a simulation whose model we have not seen
    // are ignored along with its states, which are counted.
    return v;
  }
  if (auto problem = CheckSensorReading(r, &outline_))
    return Reject(problem->fault == MessageFault::kNonFinite ? Rejection::kNonFinite
                                                             : Rejection::kBadReading,
                  "SIM_SENSOR", problem->message + ": ignored");
  v.accepted = true;
  if (r.kind == sensor_t::KIND_SCANNER) {
    scans_[r.sensor] = r;
    ++version_;
  }
  return v;
}

Eigen::Isometry3d Scene::BodyPose(int i) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (!model_ || i < 0 || i >= model_->num_bodies) return pose;
  const double* p = model_->bodies[static_cast<size_t>(i)].initial_position;
  const double* q = model_->bodies[static_cast<size_t>(i)].initial_orientation;
  if (state_) {
    p = state_->bodies[static_cast<size_t>(i)].position;
    q = state_->bodies[static_cast<size_t>(i)].orientation;
  }
  pose.linear() = Quat(q).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return pose;
}

Eigen::Vector3d Scene::Up() const {
  if (!model_) return Eigen::Vector3d::UnitY();
  return Eigen::Vector3d(model_->up[0], model_->up[1], model_->up[2]).normalized();
}

std::optional<Eigen::Vector3d> Scene::FollowPoint() const {
  if (!model_) return std::nullopt;
  const bool has_robot = model_->num_robots > 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int i = 0; i < model_->num_bodies; ++i) {
    const body_t& b = model_->bodies[static_cast<size_t>(i)];
    if (has_robot ? b.robot != 0 : b.is_static) continue;
    sum += BodyPose(i).translation();
    ++n;
  }
  if (n == 0) return std::nullopt;
  return sum / n;
}

std::pair<Eigen::Vector3d, double> Scene::FocusSphere() const {
  if (!model_) return {Eigen::Vector3d::Zero(), 5.0};
  // The bodies of robot 0, else all bodies.
  std::vector<int> chosen;
  for (int pass = 0; pass < 2 && chosen.empty(); ++pass)
    for (int i = 0; i < model_->num_bodies; ++i)
      if (pass == 1 || model_->bodies[static_cast<size_t>(i)].robot == 0) chosen.push_back(i);
  if (chosen.empty()) {
    const heightfield_t& h = model_->heightfield;
    if (h.present)
      return {Eigen::Vector3d(h.position[0], h.position[1], h.position[2]),
              0.5 * std::hypot(h.width, h.depth)};
    return {Eigen::Vector3d::Zero(), 5.0};
  }
  Eigen::AlignedBox3d box;
  for (int i : chosen) {
    const double extent = BoundingRadius(model_->bodies[static_cast<size_t>(i)].geometry);
    const Eigen::Vector3d c = BodyPose(i).translation();
    box.extend(c - Eigen::Vector3d::Constant(extent));
    box.extend(c + Eigen::Vector3d::Constant(extent));
  }
  return {box.center(), 0.5 * box.diagonal().norm()};
}

}  // namespace simpartner::viewer
