// A world file: gravity, ground, collision space, materials, heightfield,
// objects and their joints, the robots placed in it (each loaded from its
// own file), then the materials every body names.
#include <cmath>
#include <map>
#include <set>

#include "parts.h"
#include "simpartner/data_paths.h"
#include "simpartner/text.h"

namespace simpartner::model {
namespace {

using detail::Reader;

void ReadGravity(Reader& reader, const xmlNode* root, World* world) {
  const xmlNode* g = xml::Child(root, "gravity");
  if (g == nullptr) return;
  const auto gravity = reader.Vector(g, "gravity");
  if (!gravity) return;
  world->gravity = *gravity;
  if (gravity->norm() > 1e4)
    reader.Error(g, "gravity of magnitude " + FormatNumber(gravity->norm(), 10) +
                        " m/s^2 is not plausible (at most 10000)");
}

// The world origin's latitude, longitude [deg] and altitude [m].
void ReadGeodeticOrigin(Reader& reader, const xmlNode* root, World* world) {
  const xmlNode* g = xml::Child(root, "geodeticOrigin");
  const auto v = reader.Vector(g, "latitude", "longitude", "altitude", "geodeticOrigin");
  if (!v) return;
  const double latitude = v->x(), longitude = v->y(), altitude = v->z();
  auto refuse = [&](const char* field, double value, const char* unit, const char* range) {
    reader.Error(xml::Child(g, field), std::string("geodeticOrigin: ") + field + " " +
                                           FormatNumber(value, 10) + " " + unit +
                                           " is out of range " + range);
  };
  if (std::abs(latitude) >= 90.0)
    refuse("latitude", latitude, "deg", "(-90, 90)");
  else if (std::abs(longitude) > 180.0)
    refuse("longitude", longitude, "deg", "[-180, 180]");
  else if (altitude < -1e4 || altitude > 1e5)
    refuse("altitude", altitude, "m", "[-10000, 100000]");
  else
    world->geodetic_origin = GeodeticOrigin{latitude, longitude, altitude, reader.Where(g)};
}

// The plane a x + b y + c z = d, kept with a unit normal.
void ReadSurface(Reader& reader, const xmlNode* root, World* world) {
  const xmlNode* s = xml::Child(root, "surface");
  if (s == nullptr) return;
  const auto a = reader.Number(xml::Child(s, "a"), "surface a");
  const auto b = reader.Number(xml::Child(s, "b"), "surface b");
  const auto c = reader.Number(xml::Child(s, "c"), "surface c");
  const auto d = reader.Number(xml::Child(s, "d"), "surface d");
  if (a && b && c && d) {
    const Eigen::Vector3d normal(*a, *b, *c);
    if (normal.norm() < 1e-9) {
      reader.Error(s, "surface normal (a, b, c) has zero length");
    } else {
      world->has_plane = true;
      world->plane << normal / normal.norm(), *d / normal.norm();
    }
  }
  world->plane_material = xml::Attribute(s, "material").value_or("");
}

void ReadCollisionSpace(const xmlNode* root, World* world) {
  const xmlNode* space = xml::Child(root, "collisionSpace");
  if (space == nullptr) return;
  const std::string type = xml::Attribute(space, "type").value_or("hash");
  world->collision_space = type == "simple"     ? CollisionSpaceKind::kSimple
                           : type == "quadtree" ? CollisionSpaceKind::kQuadTree
                                                : CollisionSpaceKind::kHash;
}

// Objects, and the joints between them or to the world itself.
void ReadObjects(Reader& reader, const xmlNode* root, World* world) {
  for (const xmlNode* n : xml::Children(root, "object"))
    if (auto b = detail::ReadBody(reader, n, "object")) world->objects.push_back(*b);
  std::set<std::string> object_names;
  for (const xmlNode* n : xml::Children(root, "object"))
    object_names.insert(xml::Attribute(n, "name").value_or(""));
  auto body_exists = [&](const std::string& name) {
    return name == detail::kWorldBodyName || object_names.count(name) > 0;
  };
  for (const xmlNode* n : xml::Children(root, "joint")) {
    if (auto joint = detail::ReadJoint(reader, n, body_exists, "the world (objects or 'world')"))
      world->joints.push_back(*joint);
  }
  detail::CheckMassRatios(reader, world->objects, world->joints, false);
}

// Loads a placed robot's file. A world copied away from models/worlds
// still finds the shipped robots (detail::ShippedCopies; *also_tried lists
// those that were not there).
RobotLoadResult LoadPlacedRobot(RobotInstance* instance, const FileReader& read,
                                std::vector<std::string>* also_tried) {
  RobotLoadResult loaded = LoadRobotFile(instance->resolved_file, read);
  if (loaded.robot || !detail::CannotOpen(loaded.diagnostics, "robot")) return loaded;
  for (const DataCandidate& candidate :
       detail::ShippedCopies(instance->file, "models/robots", instance->resolved_file)) {
    RobotLoadResult other = LoadRobotFile(candidate.path, read);
    if (!detail::CannotOpen(other.diagnostics, "robot")) {
      instance->resolved_file = candidate.path;
      return other;
    }
    also_tried->push_back(candidate.path + " (" + candidate.source + ")");
  }
  return loaded;
}

// One line at the placing element for a robot that did not load.
void ReportUnloadedRobot(Reader& reader, const xmlNode* n, const RobotInstance& instance,
                         const DiagnosticList& problems,
                         const std::vector<std::string>& also_tried) {
  std::string tried;
  for (const std::string& t : also_tried) tried += (tried.empty() ? "" : ", ") + t;
  if (!tried.empty()) tried = "; also looked for it at " + tried;
  reader.Error(n, "robot '" + instance.name + "': cannot load '" + instance.file + "' (" +
                      std::to_string(problems.size()) + " problem" +
                      (problems.size() == 1 ? "" : "s") + ")" + tried);
}

// Robots: each file is loaded and its diagnostics kept as they are
// (pointing into the robot file), plus one line at the placing element.
void ReadPlacedRobots(Reader& reader, const xmlNode* root, const FileReader& read, World* world,
                      DiagnosticList* diagnostics) {
  std::map<int, std::string> ports;
  for (const xmlNode* n : xml::Children(root, "robot")) {
    RobotInstance instance;
    instance.name = xml::Attribute(n, "name").value_or("");
    instance.file = xml::Attribute(n, "file").value_or("");
    instance.where = reader.Where(n);
    instance.resolved_file = detail::ResolveBeside(reader.file(), instance.file);
    if (const xmlNode* t = xml::Child(n, "transformation")) {
      if (const auto placement =
              reader.Transformation(t, "robot '" + instance.name + "' transformation"))
        instance.placement = *placement;
    }
    std::vector<std::string> also_tried;
    RobotLoadResult loaded = LoadPlacedRobot(&instance, read, &also_tried);
    if (!loaded.robot) {
      ReportUnloadedRobot(reader, n, instance, loaded.diagnostics, also_tried);
      diagnostics->Append(loaded.diagnostics);
      continue;
    }
    instance.robot = std::move(*loaded.robot);
    detail::CheckPlacement(reader, n, instance);
    detail::CheckUniquePorts(reader, instance.robot, &ports, n, instance.name);
    world->robots.push_back(std::move(instance));
  }
}

// Materials: robots may define their own; the world's definitions win.
// A material whose values are wrong is reported as such, not as missing.
void CheckWorldMaterials(Reader& reader, const xmlNode* root, World* world) {
  for (const RobotInstance& r : world->robots) {
    for (const Material& m : r.robot.materials)
      if (world->FindMaterial(m.name) == nullptr) world->materials.push_back(m);
  }
  std::set<std::string> declared;
  for (const xmlNode* n : xml::Children(root, "material"))
    declared.insert(xml::Attribute(n, "name").value_or(""));
  auto exists = [&](const std::string& name) {
    return world->FindMaterial(name) != nullptr || declared.count(name) > 0;
  };
  detail::CheckMaterialNames(reader, world->objects, "object", exists, "the world");
  for (const RobotInstance& r : world->robots)
    detail::CheckMaterialNames(reader, r.robot.bodies, "body", exists, "the world or the robot");
  auto world_material = [&](const std::string& name) { return world->FindMaterial(name); };
  detail::CheckRollingBodies(reader, world->objects, world->joints, "object", world_material);
  // The robot's own materials were checked with it.
  auto declared_material = [&](const std::string& name) {
    return declared.count(name) > 0 ? world->FindMaterial(name) : nullptr;
  };
  for (const RobotInstance& r : world->robots)
    detail::CheckRollingBodies(reader, r.robot.bodies, r.robot.joints, "body", declared_material);
  detail::CheckNoSoilOnBodies(reader, world->objects, "object", "", world_material);
  for (const RobotInstance& r : world->robots)
    detail::CheckNoSoilOnBodies(reader, r.robot.bodies, "body", r.name, declared_material);
  if (!world->plane_material.empty() && !exists(world->plane_material))
    reader.Error(xml::Child(root, "surface"),
                 "surface material '" + world->plane_material + "' is not defined");
  if (world->heightfield && !world->heightfield->material.empty() &&
      !exists(world->heightfield->material))
    reader.Error(xml::Child(root, "heightfield"),
                 "heightfield material '" + world->heightfield->material + "' is not defined");
}

}  // namespace

WorldLoadResult ParseWorld(const std::string& xml, const std::string& file_name,
                           const FileReader& read) {
  WorldLoadResult result;
  const std::optional<xml::Document> doc = xml::Document::Read(
      xml, file_name, "world", xml::Dtd{"world.dtd", WorldDtd()}, &result.diagnostics);
  if (!doc) return result;
  Reader reader(file_name, &result.diagnostics);
  const xmlNode* root = doc->root();
  World world;
  world.file = file_name;
  world.name = xml::Attribute(root, "name").value_or("");
  world.description = xml::Text(xml::Child(root, "description"));
  ReadGravity(reader, root, &world);
  ReadGeodeticOrigin(reader, root, &world);
  ReadSurface(reader, root, &world);
  ReadCollisionSpace(root, &world);
  detail::SoilLibraries soil_libraries(read, &result.diagnostics);
  for (const xmlNode* n : xml::Children(root, "material"))
    if (auto m = detail::ReadMaterial(reader, n, &soil_libraries)) world.materials.push_back(*m);
  if (const xmlNode* h = xml::Child(root, "heightfield"))
    world.heightfield = detail::ReadHeightfield(reader, h);
  ReadObjects(reader, root, &world);
  ReadPlacedRobots(reader, root, read, &world, &result.diagnostics);
  CheckWorldMaterials(reader, root, &world);
  if (result.diagnostics.empty()) result.world = std::move(world);
  return result;
}

WorldLoadResult LoadWorldFile(const std::string& path, const FileReader& read) {
  std::string xml;
  WorldLoadResult result;
  if (!detail::ReadModelFile(path, read, "world", &xml, &result.diagnostics)) return result;
  return ParseWorld(xml, path, read);
}

}  // namespace simpartner::model
