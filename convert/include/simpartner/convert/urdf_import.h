// URDF (liburdfdom's parser) to our robot XML. URDF is z-up (x forward,
// y left, z up); our robot files are y-up (x forward, y up, z right), so
// every position and direction v becomes (v.x, v.z, -v.y). A body's own
// axes stay those of its URDF collision frame, so box sizes and cylinder
// axes (z) carry over unchanged. docs/convert.md has the whole mapping.
#pragma once

#include <string>
#include <vector>

#include "simpartner/diagnostic.h"

namespace simpartner::convert {

// Input that cannot be converted; every diagnostic names file and line.
class ConvertError : public DiagnosticError {
 public:
  using DiagnosticError::DiagnosticError;
};

struct UrdfImportOptions {
  // A mesh collision shape becomes the box of its bounding box (read from
  // an STL or OBJ file) instead of an error.
  bool mesh_as_box = false;
};

struct UrdfImportResult {
  std::string robot_xml;           // our robot file, already checked by our loader
  std::vector<std::string> notes;  // what changed on the way (e.g. a mesh made a box)
};

// Converts URDF text; file_name is used in messages and to find mesh files
// (relative to its directory). Throws ConvertError.
UrdfImportResult ImportUrdf(const std::string& urdf_text, const std::string& file_name,
                            const UrdfImportOptions& options = {});

// Axis-aligned bounding box of a mesh file (binary or ASCII STL, OBJ), in
// the mesh's own units; throws ConvertError saying why it cannot.
struct MeshBounds {
  double min[3];
  double max[3];
};
MeshBounds ReadMeshBounds(const std::string& path);

}  // namespace simpartner::convert
