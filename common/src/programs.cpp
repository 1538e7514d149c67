#include "simpartner/programs.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

namespace simpartner {
namespace {

namespace fs = std::filesystem;

fs::path OwnDirectory() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : self.parent_path();
}

bool IsExecutable(const fs::path& path) {
  return fs::is_regular_file(path) && ::access(path.c_str(), X_OK) == 0;
}

}  // namespace

const std::vector<ProgramPlace>& Programs() {
  static const std::vector<ProgramPlace> kPrograms = {
      {"simpartner-sim", "sim_core"},       {"simpartner-viewer", "viewer"},
      {"simpartner-camera", "camera"},
      {"simpartner-logger", "logger"},      {"simpartner-query", "logger"},
      {"simpartner-sequencer", "sequencer"}, {"simpartner-teleop", "teleop"},
      {"simpartner-teleop-vpad", "teleop"}, {"simpartner-cmd", "client"},
      {"simpartner-convert", "convert"},    {"simpartner-validate", "validate"},
      {"simpartner-batch", "batch"},        {"drive_circle", "examples"},
      {"drive_to_point", "examples"},       {"stop_at_wall", "examples"},
  };
  return kPrograms;
}

std::string_view ProgramFolder(std::string_view name) {
  for (const ProgramPlace& p : Programs())
    if (p.name == name) return p.folder;
  return {};
}

std::string SiblingProgram(std::string_view name) {
  const fs::path dir = OwnDirectory();
  if (dir.empty()) return "";
  if (IsExecutable(dir / name)) return (dir / name).string();
  const std::string_view folder = ProgramFolder(name);
  if (!folder.empty() && IsExecutable(dir / ".." / folder / name))
    return (dir / ".." / folder / name).lexically_normal().string();
  return "";
}

std::string ProgramOnPath(std::string_view name) {
  const char* path = std::getenv("PATH");
  std::string_view folders = path != nullptr ? path : "";
  while (!folders.empty()) {
    const size_t colon = folders.find(':');
    const std::string_view folder = folders.substr(0, colon);
    folders = colon == std::string_view::npos ? std::string_view() : folders.substr(colon + 1);
    if (folder.empty()) continue;
    const fs::path candidate = fs::path(folder) / name;
    if (IsExecutable(candidate)) return candidate.string();
  }
  return "";
}

std::string FindProgram(std::string_view name) {
  if (name.empty()) return "";
  if (name.find('/') != std::string_view::npos)
    return IsExecutable(fs::path(name)) ? std::string(name) : "";
  if (std::string beside = SiblingProgram(name); !beside.empty()) return beside;
  return ProgramOnPath(name);
}

}  // namespace simpartner
