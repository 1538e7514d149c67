#include "simpartner/data_paths.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

// Set for this file by common/CMakeLists.txt.
#ifndef SP_DATA_SOURCE_DIR
#error "SP_DATA_SOURCE_DIR must be defined (the source tree)"
#endif
#ifndef SP_DATA_BUILD_DIR
#error "SP_DATA_BUILD_DIR must be defined (the build tree)"
#endif
#ifndef SP_DATA_INSTALL_DIR
#error "SP_DATA_INSTALL_DIR must be defined (<prefix>/share/simpartner)"
#endif

namespace simpartner {

namespace fs = std::filesystem;

namespace {

// The running program's file; empty when /proc is not there.
fs::path ProgramFile() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : exe;
}

// Whether path lies inside directory (both made absolute and normal).
bool IsInside(const fs::path& path, const fs::path& directory) {
  const fs::path p = path.lexically_normal();
  const fs::path d = directory.lexically_normal();
  auto pi = p.begin();
  for (auto di = d.begin(); di != d.end(); ++di, ++pi) {
    if (di->empty()) continue;  // the trailing "" of "a/b/"
    if (pi == p.end() || *pi != *di) return false;
  }
  return true;
}

DiagnosticList NotFoundDiagnostic(const std::string& name, const std::string& kind,
                                  const std::vector<DataCandidate>& tried) {
  DiagnosticList list;
  list.Add(name, 0, "",
           "cannot read " + kind + " file: not found; tried:\n" + FormatCandidates(tried) +
               "(" + DescribeDataLookup() + ")");
  return list;
}

template <class Predicate>
std::string FindFirst(const std::string& name, const std::string& kind,
                      const std::vector<DataCandidate>& candidates, Predicate is_wanted) {
  for (const DataCandidate& c : candidates) {
    std::error_code error;
    // As given: the name itself, so that messages show what the user wrote.
    if (is_wanted(fs::path(c.path), error)) return &c == &candidates.front() ? name : c.path;
  }
  throw DataFileNotFound(name, kind, candidates);
}

}  // namespace

std::vector<DataRoot> DataRoots() {
  std::vector<DataRoot> roots;
  auto add = [&roots](const fs::path& directory, const std::string& source) {
    if (directory.empty()) return;
    const std::string normal = directory.lexically_normal().string();
    for (const DataRoot& r : roots)
      if (fs::path(r.directory).lexically_normal() == fs::path(normal)) return;
    roots.push_back(DataRoot{normal, source});
  };
  if (const char* env = std::getenv(kDataEnvironmentVariable)) {
    const std::string list = env;
    size_t start = 0;
    while (start <= list.size()) {
      const size_t colon = list.find(':', start);
      const std::string entry =
          list.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
      if (!entry.empty()) add(fs::absolute(entry), kDataEnvironmentVariable);
      if (colon == std::string::npos) break;
      start = colon + 1;
    }
  }
  const fs::path program = ProgramFile();
  // A program of the build tree uses the data of the sources it was built
  // from; an installed one never looks there (the tree may be gone, or
  // newer than the install).
  const bool in_build_tree = !program.empty() && IsInside(program, SP_DATA_BUILD_DIR);
  if (in_build_tree) add(SP_DATA_SOURCE_DIR, "source tree");
  if (!program.empty() && !in_build_tree)
    add(program.parent_path().parent_path() / "share" / "simpartner",
        "beside the program's bin/");
  add(SP_DATA_INSTALL_DIR, "install prefix");
  return roots;
}

namespace {

bool InBuildTree() {
  const fs::path program = ProgramFile();
  return !program.empty() && IsInside(program, SP_DATA_BUILD_DIR);
}

// ${XDG_STATE_HOME:-$HOME/.local/state}/simpartner, as simpartner-mariadb
// computes it (a relative XDG_STATE_HOME is ignored).
DataRoot InstalledStateDirectory() {
  const char* xdg = std::getenv("XDG_STATE_HOME");
  const char* home = std::getenv("HOME");
  if (xdg != nullptr && fs::path(xdg).is_absolute())
    return DataRoot{(fs::path(xdg) / "simpartner").lexically_normal().string(), "XDG_STATE_HOME"};
  if (home != nullptr && *home != '\0')
    return DataRoot{(fs::path(home) / ".local/state/simpartner").lexically_normal().string(),
                    "$HOME/.local/state"};
  return DataRoot{};
}

DataRoot StateFromEnvironment() {
  const char* state = std::getenv(kStateEnvironmentVariable);
  if (state == nullptr || *state == '\0') return DataRoot{};
  return DataRoot{fs::absolute(state).lexically_normal().string(), kStateEnvironmentVariable};
}

}  // namespace

DataRoot StateDirectory() {
  const DataRoot from_environment = StateFromEnvironment();
  if (!from_environment.directory.empty()) return from_environment;
  if (InBuildTree()) return DataRoot{};
  return InstalledStateDirectory();
}

std::vector<DataRoot> PrivateServerDirectories() {
  std::vector<DataRoot> out;
  auto add = [&out](const fs::path& state, const std::string& source) {
    const std::string directory = (state / "mariadb").lexically_normal().string();
    for (const DataRoot& r : out)
      if (r.directory == directory) return;
    out.push_back(DataRoot{directory, source});
  };
  const DataRoot from_environment = StateFromEnvironment();
  if (!from_environment.directory.empty()) add(from_environment.directory, from_environment.source);
  add(fs::absolute("state"), "working directory");
  if (InBuildTree()) {
    add(fs::path(SP_DATA_SOURCE_DIR) / "state", "source tree");
  } else {
    const DataRoot installed = InstalledStateDirectory();
    if (!installed.directory.empty()) add(installed.directory, installed.source);
  }
  return out;
}

std::vector<DataCandidate> PrivateServerFileCandidates(const std::string& name,
                                                       const std::vector<DataRoot>& directories) {
  if (fs::path(name).is_absolute()) return {DataCandidate{name, "as given"}};
  std::vector<DataCandidate> out;
  for (const DataRoot& d : directories)
    out.push_back(DataCandidate{(fs::path(d.directory) / name).lexically_normal().string(), d.source});
  return out;
}

std::vector<DataCandidate> DataFileCandidates(const std::string& name,
                                              const std::vector<std::string>& kind_dirs,
                                              const std::vector<DataRoot>& roots) {
  std::vector<DataCandidate> out;
  auto add = [&out](const fs::path& path, const std::string& source) {
    const std::string p = path.lexically_normal().string();
    for (const DataCandidate& c : out)
      if (c.path == p) return;
    out.push_back(DataCandidate{p, source});
  };
  const fs::path given(name);
  add(given.is_relative() ? fs::absolute(given) : given, "as given");
  if (name.empty() || given.is_absolute()) return out;
  for (const DataRoot& root : roots) {
    add(fs::path(root.directory) / given, root.source);
    for (const std::string& dir : kind_dirs)
      add(fs::path(root.directory) / dir / given.filename(), root.source);
  }
  return out;
}

DataFileNotFound::DataFileNotFound(std::string name, std::string kind,
                                   std::vector<DataCandidate> tried)
    : ConfigError(NotFoundDiagnostic(name, kind, tried)),
      name_(std::move(name)),
      kind_(std::move(kind)),
      tried_(std::move(tried)) {}

std::string FindDataFile(const std::string& name, const std::string& kind,
                         const std::vector<std::string>& kind_dirs,
                         const std::vector<DataRoot>& roots) {
  // Anything but a directory: the reader says why a device or FIFO is refused.
  return FindFirst(name, kind, DataFileCandidates(name, kind_dirs, roots),
                   [](const fs::path& p, std::error_code& e) {
                     return fs::exists(p, e) && !fs::is_directory(p, e);
                   });
}

std::string FindDataDirectory(const std::string& name, const std::string& kind,
                              const std::vector<DataRoot>& roots) {
  return FindFirst(name, kind, DataFileCandidates(name, {}, roots),
                   [](const fs::path& p, std::error_code& e) { return fs::is_directory(p, e); });
}

std::string FormatCandidates(const std::vector<DataCandidate>& candidates) {
  std::string out;
  for (const DataCandidate& c : candidates) out += "  " + c.path + " (" + c.source + ")\n";
  return out;
}

std::string DescribeDataLookup() {
  return std::string("data files are looked for as given, then under $") +
         kDataEnvironmentVariable +
         ", the source tree (programs of a build tree), <program dir>/../share/simpartner "
         "and " SP_DATA_INSTALL_DIR;
}

}  // namespace simpartner
