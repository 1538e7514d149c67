// SimPartner's programs and where each is built: one table, for a program
// that starts another (simpartner-batch starts sims, loggers and
// controllers) and for the tests. In a build tree a program sits in the
// folder of its source (build/sim_core/simpartner-sim), installed in one
// bin/ beside the others.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace simpartner {

struct ProgramPlace {
  std::string_view name;    // "simpartner-sim"
  std::string_view folder;  // its source folder, and build tree folder: "sim_core"
};

// Every program of the project (the benches aside).
const std::vector<ProgramPlace>& Programs();

// The folder of `name` in a build tree, or "" for a name the table lacks.
std::string_view ProgramFolder(std::string_view name);

// `name` beside the running program: <its dir>/name (installed), else
// <its dir>/../<folder>/name (a build tree); "" when neither exists (the
// caller may then look on PATH).
std::string SiblingProgram(std::string_view name);

// The first executable `name` in $PATH's folders, as a shell finds it
// (posix_spawn does not look); empty entries, which a shell reads as the
// current directory, are passed over. "" when there is none.
std::string ProgramOnPath(std::string_view name);

// `name` as a program to start: a path (it holds a '/') as given when it
// is an executable file; else SiblingProgram(name); else
// ProgramOnPath(name). "" when there is none.
std::string FindProgram(std::string_view name);

}  // namespace simpartner
