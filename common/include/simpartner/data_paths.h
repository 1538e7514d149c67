// Where a program finds SimPartner's shipped data (models/worlds,
// models/robots, sequences, parameters.txt, teleop/mappings, java/): one
// lookup for every program, so that each runs from any directory.
//
// A name is looked for, in order:
//   1. as given (relative to the working directory, or absolute);
//   2. under each directory of $SIMPARTNER_DATA (colon-separated);
//   3. under the source tree, when the program runs from its build tree;
//   4. under <directory of the program>/../share/simpartner (an install
//      moved to another prefix, e.g. cmake --install --prefix P);
//   5. under the configured prefix's share/simpartner.
// Data roots share the source tree's layout: ROOT/models/worlds/x.xml.
#pragma once

#include <string>
#include <vector>

#include "simpartner/diagnostic.h"

namespace simpartner {

inline constexpr const char* kDataEnvironmentVariable = "SIMPARTNER_DATA";

struct DataRoot {
  std::string directory;
  std::string source;  // why it is searched: "SIMPARTNER_DATA", "source tree", ...
};

// The roots of steps 2 to 5 for this process, in order, without duplicates
// (whether or not they exist).
std::vector<DataRoot> DataRoots();

// One place a name was looked for.
struct DataCandidate {
  std::string path;
  std::string source;  // "as given" or the root's source
};

// Every path FindDataFile tries for name, in order. A relative name is
// tried as given, then under each root as ROOT/name and, for each of
// kind_dirs (e.g. "models/worlds"), as ROOT/KIND_DIR/<file name of name>.
// An absolute name is tried as given only.
std::vector<DataCandidate> DataFileCandidates(const std::string& name,
                                              const std::vector<std::string>& kind_dirs,
                                              const std::vector<DataRoot>& roots);

// A data file that is in none of the places looked at. A ConfigError with
// one diagnostic at the name: "NAME: cannot read KIND file: not found;
// tried: ...", listing every full path.
class DataFileNotFound : public ConfigError {
 public:
  DataFileNotFound(std::string name, std::string kind, std::vector<DataCandidate> tried);
  const std::string& name() const { return name_; }
  const std::string& kind() const { return kind_; }
  const std::vector<DataCandidate>& tried() const { return tried_; }

 private:
  std::string name_;
  std::string kind_;
  std::vector<DataCandidate> tried_;
};

// The first candidate that exists and is not a directory (a FIFO counts:
// the reader refuses it saying why), or, for FindDataDirectory, a
// directory. kind names the file in the error ("world", "sequence").
// Throws DataFileNotFound.
std::string FindDataFile(const std::string& name, const std::string& kind,
                         const std::vector<std::string>& kind_dirs = {},
                         const std::vector<DataRoot>& roots = DataRoots());
std::string FindDataDirectory(const std::string& name, const std::string& kind,
                              const std::vector<DataRoot>& roots = DataRoots());

// "  PATH (SOURCE)" lines, one per candidate, for messages and --help.
std::string FormatCandidates(const std::vector<DataCandidate>& candidates);

// The lookup order in words, for --help texts.
std::string DescribeDataLookup();

// Where the private MariaDB server of simpartner-mariadb (scripts/mariadb
// in a source tree) keeps its files, the client option files logger.cnf,
// reader.cnf and admin.cnf among them. The script's default directory is
// $SIMPARTNER_STATE/mariadb when that is set, else <source tree>/state/mariadb
// for the script of a source tree, else (installed)
// ${XDG_STATE_HOME:-$HOME/.local/state}/simpartner/mariadb. A program
// looks, in order, in:
//   1. $SIMPARTNER_STATE/mariadb, when SIMPARTNER_STATE is set;
//   2. state/mariadb of the working directory;
//   3. the source tree's state/mariadb, when the program runs from its
//      build tree;
//   4. ${XDG_STATE_HOME:-$HOME/.local/state}/simpartner/mariadb, when it
//      does not (an installed program; a relative XDG_STATE_HOME is
//      ignored, as the XDG rule says).
inline constexpr const char* kStateEnvironmentVariable = "SIMPARTNER_STATE";

// Where this process keeps what it writes between runs (simpartner-mariadb's
// mariadb/, the logger's logger-spool/): $SIMPARTNER_STATE when set; else
// for a program of a build tree nothing (its state/ is relative to the
// working directory, as scripts/run uses it); else (installed)
// ${XDG_STATE_HOME:-$HOME/.local/state}/simpartner. directory is empty when
// there is none.
DataRoot StateDirectory();

// The directories of steps 1 to 4 for this process, without duplicates
// (whether or not they exist).
std::vector<DataRoot> PrivateServerDirectories();

// Every path of the private server's file name (e.g. "reader.cnf") under
// each of those directories; an absolute name is tried as given only.
std::vector<DataCandidate> PrivateServerFileCandidates(
    const std::string& name, const std::vector<DataRoot>& directories = PrivateServerDirectories());

}  // namespace simpartner
