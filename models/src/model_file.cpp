// Reading a model file's bytes: regular files only, never more than
// kMaxModelFileBytes, and the reason when it cannot be read.
#include <filesystem>

#include "parts.h"
#include "simpartner/bounded_file.h"

namespace simpartner::model {
namespace detail {

// Reads a model file through reader; on failure adds a diagnostic at the
// file (the reader's reason when it gave one) and returns false.
bool ReadModelFile(const std::string& path, const FileReader& read, const char* kind,
                   std::string* xml, DiagnosticList* diagnostics) {
  try {
    if (read(path, xml)) return true;
    diagnostics->Add(path, 0, "", std::string("cannot read ") + kind + " file");
  } catch (const ModelFileError& e) {
    diagnostics->Add(path, 0, "",
                     e.cannot_open() ? std::string("cannot read ") + kind + " file: " + e.what()
                                     : std::string(e.what()));
  }
  return false;
}

bool CannotOpen(const DiagnosticList& diagnostics, const char* kind) {
  return diagnostics.size() == 1 && diagnostics.items()[0].line == 0 &&
         diagnostics.items()[0].message.rfind(std::string("cannot read ") + kind + " file", 0) ==
             0;
}

std::string ResolveBeside(const std::string& from_file, const std::string& named) {
  const std::filesystem::path path(named);
  if (!path.is_relative()) return named;
  return (std::filesystem::path(from_file).parent_path() / path).lexically_normal().string();
}

std::vector<DataCandidate> ShippedCopies(const std::string& named, const char* folder,
                                         const std::string& skip) {
  const std::filesystem::path path(named);
  std::vector<DataCandidate> out;
  if (!path.is_relative()) return out;
  for (const DataRoot& root : DataRoots()) {
    const std::string candidate =
        (std::filesystem::path(root.directory) / folder / path.filename())
            .lexically_normal()
            .string();
    if (candidate != skip) out.push_back(DataCandidate{candidate, root.source});
  }
  return out;
}

}  // namespace detail

bool ReadFileFromDisk(const std::string& path, std::string* contents) {
  try {
    *contents = ReadBoundedFile(path, static_cast<size_t>(kMaxModelFileBytes), "model files");
  } catch (const FileReadError& e) {
    throw ModelFileError(e.what(), e.cannot_open());
  }
  return true;
}

}  // namespace simpartner::model
