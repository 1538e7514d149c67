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
#include "simpartner/data_paths.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/soil_library.h"

namespace simpartner::model::detail {

// soil_library.cpp: the soil libraries one world's materials name, each
// read once through read; their problems go to diagnostics.
class SoilLibraries {
 public:
  SoilLibraries(FileReader read, DiagnosticList* diagnostics)
      : read_(std::move(read)), diagnostics_(diagnostics) {}
  // The library named (as a <soil library=...> of world_file names it), or
  // null with *why ("2 problems; also looked for it at ...").
  const SoilLibrary* Get(const std::string& world_file, const std::string& named,
                         std::string* why);

 private:
  struct Loaded {
    SoilLibraryLoadResult result;
    std::string also_tried;
  };
  FileReader read_;
  DiagnosticList* diagnostics_;
  std::map<std::string, Loaded> loaded_;
};

// soil_reader.cpp
// The figures among node's children into *soil, their element names into
// *given; a figure that is not a finite number is reported (false).
bool ReadSoilFigures(Reader& reader, const xmlNode* node, const std::string& what,
                     SoilParameters* soil, std::vector<std::string>* given);
// Every figure of soil in its physical range; each problem reported at its
// element among node's children (else at node); false when any.
bool CheckSoilRanges(Reader& reader, const xmlNode* node, const std::string& what,
                     const SoilParameters& soil);
// A world's <soil> of the material material_name: a library entry, with
// the figures the world gives instead, or every figure written out.
std::optional<SoilParameters> ReadSoil(Reader& reader, const xmlNode* node,
                                       const std::string& material_name,
                                       SoilLibraries* libraries);

// material_reader.cpp; soils: where a world's <soil> finds its libraries
// (null for a robot file, which has none).
std::optional<Material> ReadMaterial(Reader& reader, const xmlNode* node,
                                     SoilLibraries* soils = nullptr);

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
// Bodies have no soil material: soil is for a ground. owner: "" for the
// world's objects, else the robot instance they belong to.
void CheckNoSoilOnBodies(Reader& reader, const std::vector<Body>& bodies, const char* element,
                         const std::string& owner,
                         const std::function<const Material*(const std::string&)>& material_of);

// model_file.cpp: reads a model file through read; on failure adds a
// diagnostic at the file (the reader's reason when it gave one) and
// returns false. kind: "world" or "robot".
bool ReadModelFile(const std::string& path, const FileReader& read, const char* kind,
                   std::string* xml, DiagnosticList* diagnostics);
// Whether loading failed only because the file could not be opened
// (ReadModelFile's one diagnostic for kind).
bool CannotOpen(const DiagnosticList& diagnostics, const char* kind);
// The file a model file (from_file) names: relative to its directory, or
// absolute.
std::string ResolveBeside(const std::string& from_file, const std::string& named);
// Where else a relative name may be: its file name in each data root's
// folder ("models/robots"), leaving out skip; none for an absolute name.
// A world copied away from models/worlds still finds the shipped files.
std::vector<DataCandidate> ShippedCopies(const std::string& named, const char* folder,
                                         const std::string& skip);

}  // namespace simpartner::model::detail
