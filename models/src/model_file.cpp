// Reading a model file's bytes: regular files only, never more than
// kMaxModelFileBytes, and the reason when it cannot be read.
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
