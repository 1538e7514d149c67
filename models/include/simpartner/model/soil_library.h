// Soil libraries (models/soils/*.xml, models/dtd/soils.dtd, docs/soil.md):
// named soils with the source of their figures, which a world's material
// takes by name. The world loader reads them itself (loader.h); programs
// that want a soil by name without a world (the validation's single-wheel
// experiments) read a library here.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/model.h"

namespace simpartner::model {

// The library shipped with SimPartner, as a world beside models/worlds
// names it.
inline constexpr const char* kShippedSoilLibrary = "../soils/wong2008.xml";

struct SoilLibrary {
  std::string file;
  std::vector<SoilParameters> soils;  // in file order, each within its ranges

  // The entry named name, or null.
  const SoilParameters* Find(const std::string& name) const;
  // "dry_sand, sandy_loam, ...", for messages.
  std::string Names() const;
};

struct SoilLibraryLoadResult {
  std::optional<SoilLibrary> library;  // set only when there were no errors
  DiagnosticList diagnostics;
};

// Parses library XML text (file_name is for messages): DTD, then every
// entry's figures within their ranges, each problem at its line.
SoilLibraryLoadResult ParseSoilLibrary(const std::string& xml, const std::string& file_name);
SoilLibraryLoadResult LoadSoilLibraryFile(const std::string& path,
                                          const FileReader& reader = ReadFileFromDisk);

// The file a program opens for a soil library name: as given, else under
// the data roots, also as models/soils/NAME (FindDataFile). Throws
// DataFileNotFound.
std::string FindSoilLibraryFile(const std::string& name);

// The soils DTD built into the library (models/dtd/soils.dtd).
const std::string& SoilsDtd();

}  // namespace simpartner::model
