// Soil library files (models/soils/*.xml): the DTD, then each entry's
// figures within their ranges; and the libraries one world's materials
// name, each read once.
#include "simpartner/model/soil_library.h"

#include "dtd_texts.h"  // generated: kSoilsDtdText
#include "parts.h"
#include "simpartner/data_paths.h"

namespace simpartner::model {

const SoilParameters* SoilLibrary::Find(const std::string& name) const {
  for (const SoilParameters& s : soils)
    if (s.name == name) return &s;
  return nullptr;
}

std::string SoilLibrary::Names() const {
  std::string out;
  for (const SoilParameters& s : soils) out += (out.empty() ? "" : ", ") + s.name;
  return out;
}

const std::string& SoilsDtd() {
  static const std::string kText(kSoilsDtdText);
  return kText;
}

std::string FindSoilLibraryFile(const std::string& name) {
  return FindDataFile(name, "soil library", {"models/soils"});
}

SoilLibraryLoadResult ParseSoilLibrary(const std::string& xml, const std::string& file_name) {
  SoilLibraryLoadResult result;
  const std::optional<xml::Document> doc = xml::Document::Read(
      xml, file_name, "soils", xml::Dtd{"soils.dtd", SoilsDtd()}, &result.diagnostics);
  if (!doc) return result;
  detail::Reader reader(file_name, &result.diagnostics);
  SoilLibrary library;
  library.file = file_name;
  for (const xmlNode* n : xml::Children(doc->root(), "soil")) {
    SoilParameters soil;
    soil.name = xml::Attribute(n, "name").value_or("");
    soil.source = xml::Attribute(n, "source").value_or("");
    soil.where = reader.Where(n);
    const std::string what = "soil '" + soil.name + "'";
    std::vector<std::string> given;  // all of them: the DTD requires every figure
    if (detail::ReadSoilFigures(reader, n, what, &soil, &given) &&
        detail::CheckSoilRanges(reader, n, what, soil))
      library.soils.push_back(std::move(soil));
  }
  if (result.diagnostics.empty()) result.library = std::move(library);
  return result;
}

SoilLibraryLoadResult LoadSoilLibraryFile(const std::string& path, const FileReader& reader) {
  std::string xml;
  SoilLibraryLoadResult result;
  if (!detail::ReadModelFile(path, reader, "soil library", &xml, &result.diagnostics))
    return result;
  return ParseSoilLibrary(xml, path);
}

namespace detail {

// A library named relative to the world file, else (a world copied away
// from models/worlds) by its file name in a data root's models/soils. Its
// own problems are reported once, however many materials name it.
const SoilLibrary* SoilLibraries::Get(const std::string& world_file, const std::string& named,
                                      std::string* why) {
  const std::string path = ResolveBeside(world_file, named);
  auto found = loaded_.find(path);
  if (found == loaded_.end()) {
    Loaded loaded{LoadSoilLibraryFile(path, read_), ""};
    if (CannotOpen(loaded.result.diagnostics, "soil library")) {
      for (const DataCandidate& c : ShippedCopies(named, "models/soils", path)) {
        SoilLibraryLoadResult other = LoadSoilLibraryFile(c.path, read_);
        if (!CannotOpen(other.diagnostics, "soil library")) {
          loaded.result = std::move(other);
          break;
        }
        loaded.also_tried +=
            (loaded.also_tried.empty() ? "" : ", ") + c.path + " (" + c.source + ")";
      }
    }
    diagnostics_->Append(loaded.result.diagnostics);
    found = loaded_.emplace(path, std::move(loaded)).first;
  }
  const Loaded& loaded = found->second;
  if (loaded.result.library) return &*loaded.result.library;
  const size_t count = loaded.result.diagnostics.size();
  *why = std::to_string(count) + " problem" + (count == 1 ? "" : "s") +
         (loaded.also_tried.empty() ? "" : "; also looked for it at " + loaded.also_tried);
  return nullptr;
}

}  // namespace detail
}  // namespace simpartner::model
