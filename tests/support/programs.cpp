#include "programs.h"

#include <stdexcept>
#include <utility>

namespace simpartner::test_support {
namespace {

struct BuiltProgramPlace {
  std::string_view name;
  std::string_view folder;
};

constexpr BuiltProgramPlace kPrograms[] = {
    {"simpartner-sim", "sim_core"},
    {"simpartner-viewer", "viewer"},
    {"simpartner-logger", "logger"},
    {"simpartner-query", "logger"},
    {"simpartner-sequencer", "sequencer"},
    {"simpartner-teleop", "teleop"},
    {"simpartner-teleop-vpad", "teleop"},
    {"simpartner-cmd", "client"},
    {"simpartner-convert", "convert"},
    {"simpartner-validate", "validate"},
    {"drive_circle", "examples"},
    {"drive_to_point", "examples"},
    {"stop_at_wall", "examples"},
};

}  // namespace

std::string SourceDir() { return SP_SOURCE_DIR; }

std::string BinaryDir() { return SP_BINARY_DIR; }

std::string BuiltProgram(std::string_view name) {
  std::string known;
  for (const BuiltProgramPlace& p : kPrograms) {
    if (p.name == name) return BinaryDir() + "/" + std::string(p.folder) + "/" + std::string(p.name);
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
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
