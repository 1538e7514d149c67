#include "simpartner/model/robot_choice.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "simpartner/data_paths.h"
#include "simpartner/edit_distance.h"
#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

constexpr const char* kRobotFlag = "--robot";
constexpr const char* kPoseFlag = "--robot-pose";
constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void Refuse(const std::string& flag, const std::string& message) {
  DiagnosticList list;
  list.Add("command line", 0, flag, message);
  throw ConfigError(list);
}

std::string ShippedNames() {
  std::string out;
  for (const ShippedRobot& r : ShippedRobots()) out += (out.empty() ? "" : ", ") + std::string(r.name);
  return out;
}

}  // namespace

const std::vector<ShippedRobot>& ShippedRobots() {
  static const std::vector<ShippedRobot> kRobots = {
      {"gen1", "workpartner_gen1.xml"}, {"gen1-light", "workpartner_gen1_light.xml"},
      {"gen2", "workpartner_gen2.xml"}, {"gen3", "workpartner_gen3.xml"},
      {"gen4", "workpartner_gen4.xml"}};
  return kRobots;
}

void ParseRobotPose(const std::string& text, RobotChoice* choice) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || errno != 0 || !std::isfinite(v))
      Refuse(kPoseFlag, "'" + item + "' in '" + text + "' is not a number (expected x,y,z or x,y,z,yaw_deg)");
    values.push_back(v);
  }
  if (values.size() != 3 && values.size() != 4)
    Refuse(kPoseFlag, "'" + text + "' has " + std::to_string(values.size()) +
                          " numbers; expected x,y,z [m] or x,y,z,yaw [m, degrees]");
  for (size_t i = 0; i < 3; ++i)
    if (std::abs(values[i]) > limits::kMaxCoordinate)
      Refuse(kPoseFlag, "coordinate " + std::to_string(values[i]) + " in '" + text +
                            "' is out of range (|x|, |y|, |z| <= 1e6 m)");
  choice->position = Eigen::Vector3d(values[0], values[1], values[2]);
  choice->yaw = values.size() == 4 ? values[3] * kPi / 180.0 : 0.0;
}

std::string RobotFileOf(const std::string& robot) {
  for (const ShippedRobot& r : ShippedRobots())
    if (robot == r.name) return FindRobotFile(std::string("models/robots/") + r.file);
  try {
    return FindRobotFile(robot);
  } catch (const DataFileNotFound& e) {
    // A short name that is not shipped: say which were meant, not where a
    // file of that name was looked for.
    const bool looks_like_file = robot.find('/') != std::string::npos ||
                                 robot.find(".xml") != std::string::npos;
    if (looks_like_file) throw;
    std::string best;
    size_t best_distance = 3;
    for (const ShippedRobot& r : ShippedRobots()) {
      const size_t d = EditDistance(robot, r.name);
      if (d < best_distance) best_distance = d, best = r.name;
    }
    Refuse(kRobotFlag, "unknown robot '" + robot + "'" +
                           (best.empty() ? std::string() : " (did you mean '" + best + "'?)") +
                           "; give one of " + ShippedNames() + " or a robot file");
  }
}

void PlaceRobot(const RobotChoice& choice, World* world) {
  RobotInstance instance;
  instance.file = RobotFileOf(choice.robot);
  instance.resolved_file = instance.file;
  instance.robot = LoadRobotOrThrow(instance.file);
  instance.where = SourceLocation{"command line", 0};

  const std::string base_name = world->robots.empty() ? "WorkPartner" : world->robots.front().name;
  if (choice.position) {
    instance.placement = Eigen::Isometry3d::Identity();
    instance.placement.translate(*choice.position);
    instance.placement.rotate(Eigen::AngleAxisd(choice.yaw, world->Up()));
  } else if (!world->robots.empty()) {
    instance.placement = world->robots.front().placement;
  }
  if (choice.add) {
    instance.name = base_name;
    for (int n = 2;; ++n) {
      bool taken = false;
      for (const RobotInstance& r : world->robots) taken = taken || r.name == instance.name;
      if (!taken) break;
      instance.name = base_name + std::to_string(n);
    }
  } else {
    instance.name = base_name;
    world->robots.clear();
    // The replaced robots' own materials go with them (the world's stay).
    std::vector<Material> kept;
    for (const Material& m : world->materials)
      if (m.where.file == world->file) kept.push_back(m);
    world->materials = std::move(kept);
  }

  // What the loader checks at a world's <robot>, for this one.
  for (const Body& b : instance.robot.bodies) {
    const Eigen::Vector3d p = instance.placement * b.pose.translation();
    if (p.cwiseAbs().maxCoeff() > limits::kMaxCoordinate)
      Refuse(kPoseFlag, "robot '" + instance.name + "': its body '" + b.name +
                            "' would be out of range (|x|, |y|, |z| <= 1e6 m)");
  }
  std::map<int, std::string> ports;
  for (const RobotInstance& r : world->robots) {
    for (const Sensor& s : r.robot.sensors) if (s.port) ports[s.port] = r.name + "/" + s.name;
    for (const Actuator& a : r.robot.actuators) if (a.port) ports[a.port] = r.name + "/" + a.name;
  }
  auto check_port = [&](int port, const std::string& name) {
    const auto it = ports.find(port);
    if (port != 0 && it != ports.end())
      Refuse(kRobotFlag, "robot '" + instance.name + "' (" + instance.file + "): '" + name +
                             "' uses port " + std::to_string(port) + ", already used by '" +
                             it->second + "' (add a robot whose file has other ports)");
  };
  for (const Sensor& s : instance.robot.sensors) check_port(s.port, s.name);
  for (const Actuator& a : instance.robot.actuators) check_port(a.port, a.name);
  for (const Body& b : instance.robot.bodies) {
    if (b.material.empty() || world->FindMaterial(b.material) != nullptr) continue;
    bool own = false;
    for (const Material& m : instance.robot.materials) own = own || m.name == b.material;
    if (!own)
      Refuse(kRobotFlag, "robot file " + instance.file + ": body '" + b.name + "' uses material '" +
                             b.material + "', defined neither in the robot nor in world '" +
                             world->name + "'");
  }
  // The robot's own materials, unless the world defines them (world wins).
  for (const Material& m : instance.robot.materials)
    if (world->FindMaterial(m.name) == nullptr) world->materials.push_back(m);
  world->robots.push_back(std::move(instance));
}

}  // namespace simpartner::model
