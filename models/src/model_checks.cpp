// What the DTD cannot say about a robot or a world as a whole: mass
// ratios ODE can take, a robot's connected graph, unique ports, defined
// materials, rolling bodies with an axis, robots placed within range.
#include <map>
#include <set>

#include "parts.h"
#include "simpartner/text.h"

namespace simpartner::model::detail {

// Mass ratios ODE's solver can take (models/README.md): across each joint
// between two moving bodies, and, when robot_wide, between the heaviest and
// the lightest moving body.
void CheckMassRatios(Reader& reader, const std::vector<Body>& bodies,
                     const std::vector<Joint>& joints, bool robot_wide) {
  using namespace limits;
  auto find = [&](const std::string& name) -> const Body* {
    for (const Body& b : bodies)
      if (b.name == name) return &b;
    return nullptr;
  };
  for (const Joint& joint : joints) {
    const Body* b1 = find(joint.body1);
    const Body* b2 = find(joint.body2);
    if (b1 == nullptr || b2 == nullptr || b1->is_static || b2->is_static) continue;
    const Body* heavy = b1->mass >= b2->mass ? b1 : b2;
    const Body* light = heavy == b1 ? b2 : b1;
    if (heavy->mass > kMaxJointMassRatio * light->mass)
      reader.ErrorAt(joint.where, "joint",
                     "joint '" + joint.name + "': body '" + heavy->name + "' (" +
                         FormatNumber(heavy->mass, 10) + " kg) is " +
                         FormatNumber(heavy->mass / light->mass, 10) + " times as heavy as body '" +
                         light->name + "' (" + FormatNumber(light->mass, 10) +
                         " kg); across a joint at most " + FormatNumber(kMaxJointMassRatio, 10));
  }
  if (!robot_wide) return;
  const Body* heaviest = nullptr;
  const Body* lightest = nullptr;
  for (const Body& b : bodies) {
    if (b.is_static) continue;
    if (heaviest == nullptr || b.mass > heaviest->mass) heaviest = &b;
    if (lightest == nullptr || b.mass < lightest->mass) lightest = &b;
  }
  if (heaviest != nullptr && heaviest->mass > kMaxRobotMassRatio * lightest->mass)
    reader.ErrorAt(lightest->where, "body",
                   "body '" + lightest->name + "' (" + FormatNumber(lightest->mass, 10) +
                       " kg) is " + FormatNumber(heaviest->mass / lightest->mass, 10) +
                       " times lighter than body '" + heaviest->name + "' (" +
                       FormatNumber(heaviest->mass, 10) + " kg); within a robot at most " +
                       FormatNumber(kMaxRobotMassRatio, 10));
}

// Bodies that no chain of joints reaches from the first body. Judged on
// what the file declares, so that it is reported along with any other
// problem; except when a joint names a body that does not exist or joins a
// body to itself (reported already): then the graph the file means is
// unknown.
void CheckConnected(Reader& reader, const xmlNode* root) {
  const std::vector<const xmlNode*> bodies = xml::Children(root, "body");
  if (bodies.empty()) return;
  std::set<std::string> names;
  for (const xmlNode* b : bodies) names.insert(xml::Attribute(b, "name").value_or(""));
  std::map<std::string, std::vector<std::string>> neighbours;
  for (const xmlNode* j : xml::Children(root, "joint")) {
    const std::string body1 = xml::Text(xml::Child(j, "body1"));
    const std::string body2 = xml::Text(xml::Child(j, "body2"));
    if (names.count(body1) == 0 || names.count(body2) == 0 || body1 == body2) return;
    neighbours[body1].push_back(body2);
    neighbours[body2].push_back(body1);
  }
  const std::string first = xml::Attribute(bodies.front(), "name").value_or("");
  std::set<std::string> reached = {first};
  std::vector<std::string> frontier = {first};
  while (!frontier.empty()) {
    const std::string name = frontier.back();
    frontier.pop_back();
    for (const std::string& next : neighbours[name])
      if (reached.insert(next).second) frontier.push_back(next);
  }
  for (const xmlNode* b : bodies) {
    const std::string name = xml::Attribute(b, "name").value_or("");
    if (reached.count(name) == 0)
      reader.Error(b, "body '" + name + "' is not connected to '" + first +
                          "' by any chain of joints (a robot is one connected graph)");
  }
}

// Legacy ports are TCP ports of one machine: unique within a robot and over
// all robots of a world. used maps each port to its owner. Within a robot
// file (placement null) a clash is reported at the second user; between
// robots (the files are fine each) at the world's <robot> that placed the
// second one.
void CheckUniquePorts(Reader& reader, const Robot& robot, std::map<int, std::string>* used,
                      const xmlNode* placement, const std::string& instance) {
  auto check = [&](int port, const std::string& name, const SourceLocation& where,
                   const char* element) {
    if (port == 0) return;
    const auto [it, inserted] =
        used->emplace(port, placement == nullptr ? name : instance + "/" + name);
    if (inserted) return;
    const std::string what = std::string(element) + " '" + name + "'";
    const std::string clash =
        "port " + std::to_string(port) + " is already used by '" + it->second + "'";
    if (placement == nullptr)
      reader.ErrorAt(where, element, what + ": " + clash);
    else
      reader.Error(placement, "robot '" + instance + "': " + what + " " + clash);
  };
  for (const Sensor& s : robot.sensors) check(s.port, s.name, s.where, "sensor");
  for (const Actuator& a : robot.actuators) check(a.port, a.name, a.where, "actuator");
}

void CheckMaterialNames(Reader& reader, const std::vector<Body>& bodies, const char* element,
                        const std::function<bool(const std::string&)>& exists,
                        const std::string& where_defined) {
  for (const Body& b : bodies) {
    if (!b.material.empty() && !exists(b.material))
      reader.ErrorAt(b.where, element,
                     std::string(element) + " '" + b.name + "': material '" + b.material +
                         "' is not defined in " + where_defined);
  }
}

// A body whose material sets friction along its rolling direction needs an
// axis it rolls about (SpinAxis in model.h says where it comes from).
void CheckRollingBodies(Reader& reader, const std::vector<Body>& bodies,
                        const std::vector<Joint>& joints, const char* element,
                        const std::function<const Material*(const std::string&)>& material_of) {
  for (const Body& b : bodies) {
    const Material* m = b.material.empty() ? nullptr : material_of(b.material);
    if (m == nullptr || m->friction_direction != FrictionDirection::kRolling) continue;
    std::string why;
    if (!SpinAxis(b, joints, &why))
      reader.ErrorAt(b.where, element,
                     std::string(element) + " '" + b.name + "': material '" + m->name + "' (" +
                         m->where.file + ":" + std::to_string(m->where.line) +
                         ") has frictionDirection rolling, but the body has no spin axis: " + why);
  }
}

// A robot's bodies and joint anchors where the world places them must lie
// within limits::kMaxCoordinate; reported once, at the placing <robot>.
void CheckPlacement(Reader& reader, const xmlNode* robot_node, const RobotInstance& instance) {
  const xmlNode* at = xml::Child(robot_node, "transformation");
  if (at == nullptr) at = robot_node;
  auto report = [&](const std::string& what, const Eigen::Vector3d& where) {
    reader.Error(at, "robot '" + instance.name + "': placed at " +
                         VectorText(instance.placement.translation()) + " m, its " + what +
                         " is at " + VectorText(where) + " m, out of range: " +
                         CoordinateRangeText());
  };
  for (const Body& b : instance.robot.bodies) {
    const Eigen::Vector3d p = instance.placement * b.pose.translation();
    if (!CoordinatesInRange(p)) return report("body '" + b.name + "'", p);
  }
  for (const Joint& j : instance.robot.joints) {
    const Eigen::Vector3d p = instance.placement * j.anchor;
    if (!CoordinatesInRange(p)) return report("joint '" + j.name + "' anchor", p);
  }
}

// A soil yields under a wheel; a body of soil would be a moving ground,
// which nothing models.
void CheckNoSoilOnBodies(Reader& reader, const std::vector<Body>& bodies, const char* element,
                         const std::string& owner,
                         const std::function<const Material*(const std::string&)>& material_of) {
  for (const Body& b : bodies) {
    const Material* m = b.material.empty() ? nullptr : material_of(b.material);
    if (m == nullptr || !m->soil) continue;
    reader.ErrorAt(b.where, element,
                   std::string(element) + " '" + b.name + "'" +
                       (owner.empty() ? "" : " of robot '" + owner + "'") + ": material '" +
                       m->name + "' (" + m->where.file + ":" + std::to_string(m->where.line) +
                       ") is a soil, and soil is only for a ground (the surface or the "
                       "heightfield)");
  }
}

}  // namespace simpartner::model::detail
