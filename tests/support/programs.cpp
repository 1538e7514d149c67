#include "programs.h"

#include <stdexcept>
#include <utility>

#include "simpartner/programs.h"

namespace simpartner::test_support {

std::string SourceDir() { return SP_SOURCE_DIR; }

std::string BinaryDir() { return SP_BINARY_DIR; }

std::string BuiltProgram(std::string_view name) {
  const std::string_view folder = ProgramFolder(name);
  if (!folder.empty()) return BinaryDir() + "/" + std::string(folder) + "/" + std::string(name);
  std::string known;
  for (const ProgramPlace& p : Programs()) known += (known.empty() ? "" : ", ") + std::string(p.name);
  throw std::invalid_argument("BuiltProgram: no program '" + std::string(name) +
                              "' in this build (known: " + known + ")");
}

std::vector<std::string> BuiltCommand(std::string_view name, const std::vector<std::string>& args) {
  std::vector<std::string> argv = {BuiltProgram(name)};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

std::string ShippedWorld(const std::string& file) { return SourceDir() + "/models/worlds/" + file; }

}  // namespace simpartner::test_support
