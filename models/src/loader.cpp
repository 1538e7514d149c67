// What the loader offers programs beyond reading (the readers are in
// robot_reader.cpp and world_reader.cpp): the built-in DTDs, where a named
// file is, the throwing forms and a summary of a world.
#include "simpartner/model/loader.h"

#include <sstream>

#include "simpartner/data_paths.h"
#include "simpartner/xml_document.h"
#include "dtd_texts.h"  // generated: kWorldDtdText, kRobotDtdText

namespace simpartner::model {

static_assert(kMaxModelFileBytes == static_cast<long long>(xml::kMaxDocumentBytes),
              "a model file that can be read can be parsed");

const std::string& WorldDtd() {
  static const std::string kText(kWorldDtdText);
  return kText;
}

const std::string& RobotDtd() {
  static const std::string kText(kRobotDtdText);
  return kText;
}

std::string FindWorldFile(const std::string& name) {
  return FindDataFile(name, "world", {"models/worlds"});
}

std::string FindRobotFile(const std::string& name) {
  return FindDataFile(name, "robot", {"models/robots"});
}

World LoadWorldOrThrow(const std::string& path) {
  WorldLoadResult result = LoadWorldFile(FindWorldFile(path));
  if (!result.world) throw ModelError(result.diagnostics);
  return std::move(*result.world);
}

Robot LoadRobotOrThrow(const std::string& path) {
  RobotLoadResult result = LoadRobotFile(FindRobotFile(path));
  if (!result.robot) throw ModelError(result.diagnostics);
  return std::move(*result.robot);
}

std::string DescribeWorld(const World& world) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << "world '" << world.name << "' (" << world.file << ")\n";
  out << "  gravity " << world.gravity.x() << " " << world.gravity.y() << " "
      << world.gravity.z() << " m/s^2, collision space " << ToString(world.collision_space)
      << (world.has_plane ? ", ground plane" : "")
      << (world.heightfield ? ", heightfield " + std::to_string(world.heightfield->rows) + "x" +
                                  std::to_string(world.heightfield->columns)
                            : std::string())
      << "\n";
  double object_mass = 0.0;
  for (const Body& b : world.objects) object_mass += b.mass;
  out << "  objects: " << world.objects.size() << " (" << object_mass << " kg), joints: "
      << world.joints.size() << ", materials: " << world.materials.size() << "\n";
  for (const RobotInstance& r : world.robots) {
    out << "  robot '" << r.name << "' = " << r.robot.model_name << " (" << r.resolved_file
        << ")\n";
    out << "    bodies: " << r.robot.bodies.size() << ", joints: " << r.robot.joints.size()
        << ", sensors: " << r.robot.sensors.size() << ", actuators: "
        << r.robot.actuators.size() << ", total mass: " << r.robot.TotalMass() << " kg\n";
  }
  return out.str();
}

}  // namespace simpartner::model
