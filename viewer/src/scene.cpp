#include "simpartner/viewer/scene.h"
#include "simpartner/text.h"

#include <cmath>
#include <sstream>

namespace simpartner::viewer {
namespace {

constexpr size_t kMaxRecentProblems = 8;
// A unit quaternion sent as doubles is unit to ~1e-15; 1e-3 lets through
// any honest rounding and catches a zero or unnormalised orientation.
constexpr double kQuaternionTolerance = 1e-3;
// Bounds on what a model may ask the viewer to build, so that a damaged
// message cannot make it allocate gigabytes.
constexpr int64_t kMaxHeightfieldSamples = 16 * 1024 * 1024;
constexpr double kMaxSize = 1e5;  // [m]

bool Finite3(const double v[3]) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

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

std::string BodyLabel(const model_t& m, int i) {
  return "body '" + m.bodies[static_cast<size_t>(i)].name + "'";
}

// First non-finite entry of a 3-vector field, as "name[k] = value".
std::optional<std::string> NonFinite(const char* field, const double v[3], int n = 3) {
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(v[k])) return std::string(field) + "[" + std::to_string(k) + "] = " + FormatNumber(v[k]);
  return std::nullopt;
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
  }
  return "?";
}

std::optional<std::string> CheckModel(const model_t& m) {
  if (m.num_bodies != static_cast<int32_t>(m.bodies.size()) || m.num_bodies < 0)
    return "num_bodies = " + std::to_string(m.num_bodies) + " but " +
           std::to_string(m.bodies.size()) + " bodies";
  if (!Finite3(m.up) || std::abs(Eigen::Vector3d(m.up[0], m.up[1], m.up[2]).norm() - 1) > 1e-3)
    return "up = (" + FormatNumber(m.up[0]) + ", " + FormatNumber(m.up[1]) + ", " + FormatNumber(m.up[2]) +
           ") is not a unit vector";
  if (m.has_plane) {
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite(m.plane[k])) return "plane[" + std::to_string(k) + "] = " + FormatNumber(m.plane[k]);
    if (Eigen::Vector3d(m.plane[0], m.plane[1], m.plane[2]).norm() < 1e-9)
      return "plane normal (a, b, c) is zero";
  }
  for (int i = 0; i < m.num_bodies; ++i) {
    const body_t& b = m.bodies[static_cast<size_t>(i)];
    const std::string where = "bodies[" + std::to_string(i) + "]";
    const geometry_t& g = b.geometry;
    int sizes = 0;
    switch (g.kind) {
      case geometry_t::KIND_NONE: sizes = 0; break;
      case geometry_t::KIND_BOX: sizes = 3; break;
      case geometry_t::KIND_SPHERE: sizes = 1; break;
      case geometry_t::KIND_CYLINDER:
      case geometry_t::KIND_CAPSULE: sizes = 2; break;
      default:
        return where + ".geometry.kind = " + std::to_string(g.kind) + " (" + BodyLabel(m, i) +
               ") is not a known kind";
    }
    for (int k = 0; k < sizes; ++k) {
      // A capsule's cylinder part may be 0 long (a sphere).
      const bool may_be_zero = g.kind == geometry_t::KIND_CAPSULE && k == 1;
      if (!std::isfinite(g.size[k]) || g.size[k] < 0 || (g.size[k] == 0 && !may_be_zero) ||
          g.size[k] > kMaxSize)
        return where + ".geometry.size[" + std::to_string(k) + "] = " + FormatNumber(g.size[k]) + " (" +
               BodyLabel(m, i) + ")";
    }
    if (auto bad = NonFinite("initial_position", b.initial_position))
      return where + "." + *bad + " (" + BodyLabel(m, i) + ")";
    const double qn = Quat(b.initial_orientation).norm();
    if (!std::isfinite(qn) || std::abs(qn - 1) > kQuaternionTolerance)
      return where + ".initial_orientation has length " + FormatNumber(qn) + " (" + BodyLabel(m, i) + ")";
    if (b.robot < -1 || b.robot >= m.num_robots)
      return where + ".robot = " + std::to_string(b.robot) + " (" + BodyLabel(m, i) + ") but " +
             std::to_string(m.num_robots) + " robots";
  }
  for (size_t j = 0; j < m.joints.size(); ++j) {
    const joint_t& joint = m.joints[j];
    for (int32_t body : {joint.body1, joint.body2})
      if (body < -1 || body >= m.num_bodies)
        return "joints[" + std::to_string(j) + "] ('" + joint.name + "') joins body " +
               std::to_string(body) + " of " + std::to_string(m.num_bodies);
    if (auto bad = NonFinite("anchor", joint.anchor))
      return "joints[" + std::to_string(j) + "]." + *bad;
  }
  for (size_t s = 0; s < m.sensors.size(); ++s) {
    const sensor_t& sensor = m.sensors[s];
    if (sensor.body < -1 || sensor.body >= m.num_bodies)
      return "sensors[" + std::to_string(s) + "] ('" + sensor.name + "').body = " +
             std::to_string(sensor.body) + " of " + std::to_string(m.num_bodies);
    if (auto bad = NonFinite("position", sensor.position))
      return "sensors[" + std::to_string(s) + "]." + *bad;
    if (!std::isfinite(Quat(sensor.orientation).norm()) || Quat(sensor.orientation).norm() < 1e-9)
      return "sensors[" + std::to_string(s) + "].orientation is not a rotation";
    for (double p : sensor.params)
      if (!std::isfinite(p)) return "sensors[" + std::to_string(s) + "].params has " + FormatNumber(p);
  }
  const heightfield_t& h = m.heightfield;
  if (h.present) {
    if (h.rows < 2 || h.columns < 2)
      return "heightfield is " + std::to_string(h.rows) + " x " + std::to_string(h.columns) +
             " samples (at least 2 x 2)";
    const int64_t count = static_cast<int64_t>(h.rows) * h.columns;
    if (count > kMaxHeightfieldSamples)
      return "heightfield has " + std::to_string(count) + " samples (at most " +
             std::to_string(kMaxHeightfieldSamples) + ")";
    if (h.num_samples != count || static_cast<int64_t>(h.samples.size()) != count)
      return "heightfield.num_samples = " + std::to_string(h.num_samples) + " but rows x columns = " +
             std::to_string(count);
    for (double v : {h.width, h.depth})
      if (!std::isfinite(v) || v <= 0 || v > kMaxSize)
        return "heightfield width/depth = " + FormatNumber(v);
    if (!std::isfinite(h.scale) || !std::isfinite(h.offset) || !Finite3(h.position))
      return "heightfield scale/offset/position is not finite";
    for (size_t k = 0; k < h.samples.size(); ++k)
      if (!std::isfinite(h.samples[k]))
        return "heightfield.samples[" + std::to_string(k) + "] = " + FormatNumber(h.samples[k]);
  }
  return std::nullopt;
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
    Verdict v = Reject(Rejection::kBadModel, "SIM_MODEL",
                       *problem + " (simulation " + std::to_string(model.simulation_id) +
                           "): model ignored");
    return v;
  }
  // Another simulation's model (a second sim on the bus, a stale or forged
  // one) does not replace the one shown (simulation_follower.h).
  if (follower_.OnModel(model.simulation_id, model.sender, SimulationFollower::Clock::now()) ==
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
    return v;
  }
  model_ = model;
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
  auto problem = CheckRuts(ruts);
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
  if (s.num_bodies != m.num_bodies || static_cast<int32_t>(s.bodies.size()) != m.num_bodies)
    return Reject(Rejection::kBodyCount, "SIM_STATE",
                  "num_bodies = " + std::to_string(s.num_bodies) + " (step " +
                      std::to_string(s.step) + "), the model has " + std::to_string(m.num_bodies) +
                      ": ignored");
  if (s.num_joints != m.num_joints || static_cast<int32_t>(s.joints.size()) != m.num_joints)
    return Reject(Rejection::kJointCount, "SIM_STATE",
                  "num_joints = " + std::to_string(s.num_joints) + " (step " +
                      std::to_string(s.step) + "), the model has " + std::to_string(m.num_joints) +
                      ": ignored");
  if (!std::isfinite(s.sim_time))
    return Reject(Rejection::kNonFinite, "SIM_STATE", "sim_time = " + FormatNumber(s.sim_time) + ": ignored");
  for (int i = 0; i < s.num_bodies; ++i) {
    const body_state_t& b = s.bodies[static_cast<size_t>(i)];
    const std::string where = "bodies[" + std::to_string(i) + "].";
    for (auto field : {std::make_pair("position", b.position),
                       std::make_pair("contact_force", b.contact_force)}) {
      if (auto bad = NonFinite(field.first, field.second))
        return Reject(Rejection::kNonFinite, "SIM_STATE",
                      where + *bad + " (" + BodyLabel(m, i) + ", step " + std::to_string(s.step) +
                          "): ignored");
    }
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite(b.orientation[k]))
        return Reject(Rejection::kNonFinite, "SIM_STATE",
                      where + "orientation[" + std::to_string(k) + "] = " + FormatNumber(b.orientation[k]) +
                          " (" + BodyLabel(m, i) + ", step " + std::to_string(s.step) + "): ignored");
    const double qn = Quat(b.orientation).norm();
    if (std::abs(qn - 1) > kQuaternionTolerance)
      return Reject(Rejection::kBadQuaternion, "SIM_STATE",
                    where + "orientation has length " + FormatNumber(qn) + " (" + BodyLabel(m, i) +
                        ", step " + std::to_string(s.step) + "): ignored");
  }
  for (int j = 0; j < s.num_joints; ++j) {
    const joint_state_t& js = s.joints[static_cast<size_t>(j)];
    const std::string where = "joints[" + std::to_string(j) + "].";
    for (auto field : {std::make_pair("anchor", js.anchor), std::make_pair("force1", js.force1)})
      if (auto bad = NonFinite(field.first, field.second))
        return Reject(Rejection::kNonFinite, "SIM_STATE",
                      where + *bad + " (joint '" + m.joints[static_cast<size_t>(j)].name +
                          "', step " + std::to_string(s.step) + "): ignored");
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
  if (!std::isfinite(status.sim_time) || !std::isfinite(status.real_time_factor))
    return Reject(Rejection::kNonFinite, "SIM_STATUS",
                  "sim_time = " + FormatNumber(status.sim_time) + ", real_time_factor = " +
                      FormatNumber(status.real_time_factor) + ": ignored");
  v.accepted = true;
  follower_.Heard(status.simulation_id, SimulationFollower::Clock::now());
  if (status.run_state == status_t::RUN_STOPPED) follower_.Ended(status.simulation_id);
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
  const std::string what = "sensor " + std::to_string(r.sensor) + " ('" + r.name + "')";
  if (r.sensor < 0 || r.sensor >= model_->num_sensors)
    return Reject(Rejection::kBadReading, "SIM_SENSOR",
                  "sensor = " + std::to_string(r.sensor) + " but the model has " +
                      std::to_string(model_->num_sensors) + " sensors: ignored");
  const sensor_t& sensor = model_->sensors[static_cast<size_t>(r.sensor)];
  if (sensor.kind != r.kind)
    return Reject(Rejection::kBadReading, "SIM_SENSOR",
                  what + ": kind = " + std::to_string(r.kind) + ", the model says " +
                      std::to_string(sensor.kind) + ": ignored");
  for (size_t k = 0; k < r.values.size(); ++k)
    if (!std::isfinite(r.values[k]))
      return Reject(Rejection::kNonFinite, "SIM_SENSOR",
                    what + ": values[" + std::to_string(k) + "] = " + FormatNumber(r.values[k]) +
                        ": ignored");
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
