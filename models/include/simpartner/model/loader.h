// Loads world and robot XML files: DTD validation (libxml2) first, then the
// physics checks the DTD cannot express. Every problem is reported with
// file, line and element; the loader keeps going to report all of them.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "simpartner/diagnostic.h"
#include "simpartner/model/model.h"

namespace simpartner::model {

// Reads a file's bytes; returns false when it cannot, or throws
// ModelFileError to say why. Injected so that tests and fuzzers can load
// worlds whose robot files live in memory.
using FileReader = std::function<bool(const std::string& path, std::string* contents)>;

// Model files larger than this are refused unread (the largest shipped
// one, test_track.xml, is about 100 KB).
inline constexpr long long kMaxModelFileBytes = 64LL * 1024 * 1024;

// Why a model file cannot be read; the loader reports it as a diagnostic
// at the file. A file that cannot be opened (missing, no permission) reads
// "cannot read world file: <why>"; one that is refused, its reason as it
// is ("not a regular file (FIFO); model files must be regular files").
class ModelFileError : public Error {
 public:
  ModelFileError(const std::string& why, bool cannot_open)
      : Error(why), cannot_open_(cannot_open) {}
  bool cannot_open() const { return cannot_open_; }

 private:
  bool cannot_open_;
};

// Reads from the file system: regular files only (a device, FIFO, socket
// or directory is refused without reading or blocking), at most
// kMaxModelFileBytes. Throws ModelFileError with the reason.
bool ReadFileFromDisk(const std::string& path, std::string* contents);

struct RobotLoadResult {
  std::optional<Robot> robot;      // set only when there were no errors
  DiagnosticList diagnostics;
};

struct WorldLoadResult {
  std::optional<World> world;      // set only when there were no errors
  DiagnosticList diagnostics;
};

// Parses robot XML text; file_name is used in messages.
RobotLoadResult ParseRobot(const std::string& xml, const std::string& file_name);
RobotLoadResult LoadRobotFile(const std::string& path,
                              const FileReader& reader = ReadFileFromDisk);

// Parses world XML text; robot files are resolved relative to file_name's
// directory, then under the data roots (data_paths.h), and read through
// reader.
WorldLoadResult ParseWorld(const std::string& xml, const std::string& file_name,
                           const FileReader& reader = ReadFileFromDisk);
WorldLoadResult LoadWorldFile(const std::string& path,
                              const FileReader& reader = ReadFileFromDisk);

// The file a program opens for a world or robot name: as given, else under
// the data roots (data_paths.h), also as models/worlds/NAME or
// models/robots/NAME. Throws DataFileNotFound listing every path tried.
std::string FindWorldFile(const std::string& name);
std::string FindRobotFile(const std::string& name);

// Throwing forms for programs (path found as above): ModelError lists every
// diagnostic; DataFileNotFound when there is no such file.
World LoadWorldOrThrow(const std::string& path);
Robot LoadRobotOrThrow(const std::string& path);

// The DTD texts built into the library (from models/dtd/).
const std::string& WorldDtd();
const std::string& RobotDtd();

// Human summary of a world: per robot its bodies, joints, sensors,
// actuators and total mass; the objects of the world.
std::string DescribeWorld(const World& world);

}  // namespace simpartner::model
