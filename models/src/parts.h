// The pieces the loader reads a world or robot file with (internal to
// sp_model). Each reports every problem through the Reader and returns
// nothing for an element that has one; the checks look at what was read.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "reader.h"
#include "simpartner/model/loader.h"

namespace simpartner::model::detail {

// material_reader.cpp
std::optional<Material> ReadMaterial(Reader& reader, const xmlNode* node);

// body_reader.cpp: <body> (robot) or <object> (world); kind_word names it
// in messages.
std::optional<Body> ReadBody(Reader& reader, const xmlNode* node, const char* kind_word);

// joint_reader.cpp: body_exists says whether a name is a body the joint
// may join (the world file allows "world"); owner names where they live.
std::optional<Joint> ReadJoint(Reader& reader, const xmlNode* node,
                               const std::function<bool(const std::string&)>& body_exists,
                               const std::string& owner);

// heightfield_reader.cpp
std::optional<Heightfield> ReadHeightfield(Reader& reader, const xmlNode* node);

// model_checks.cpp
// Mass ratios ODE's solver can take (models/README.md): across each joint
// between two moving bodies, and, when robot_wide, between the heaviest and
// the lightest moving body.
void CheckMassRatios(Reader& reader, const std::vector<Body>& bodies,
                     const std::vector<Joint>& joints, bool robot_wide);
// Every body of the robot root reached from the first by joints.
void CheckConnected(Reader& reader, const xmlNode* root);
// Legacy ports unique; used maps each port to its owner. placement: the
// world's <robot> element that placed robot (null within a robot file).
void CheckUniquePorts(Reader& reader, const Robot& robot, std::map<int, std::string>* used,
                      const xmlNode* placement, const std::string& instance);
// Every material a body names exists.
void CheckMaterialNames(Reader& reader, const std::vector<Body>& bodies, const char* element,
                        const std::function<bool(const std::string&)>& exists,
                        const std::string& where_defined);
// Bodies of a rolling material have an axis to roll about.
void CheckRollingBodies(Reader& reader, const std::vector<Body>& bodies,
                        const std::vector<Joint>& joints, const char* element,
                        const std::function<const Material*(const std::string&)>& material_of);
// A placed robot lies within the coordinate range.
void CheckPlacement(Reader& reader, const xmlNode* robot_node, const RobotInstance& instance);

// model_file.cpp: reads a model file through read; on failure adds a
// diagnostic at the file (the reader's reason when it gave one) and
// returns false. kind: "world" or "robot".
bool ReadModelFile(const std::string& path, const FileReader& read, const char* kind,
                   std::string* xml, DiagnosticList* diagnostics);

}  // namespace simpartner::model::detail
