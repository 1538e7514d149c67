#include "simpartner/convert/convert.h"

#include <fstream>
#include <sstream>

#include "simpartner/convert/mjcf_export.h"
#include "simpartner/convert/urdf_import.h"
#include "simpartner/data_paths.h"
#include "simpartner/model/loader.h"
#include "xml_lines.h"

namespace simpartner::convert {
namespace {

ConvertError Located(const std::string& file, int line, const std::string& message) {
  DiagnosticList diagnostics;
  diagnostics.Add(file, line, "", message);
  return ConvertError(diagnostics);
}

constexpr const char* kUsage =
    "usage: simpartner-convert IN -o OUT [--mesh-as-box] [--params FILE] [--key=value ...]\n"
    "\n"
    "Converts a robot model; the direction comes from IN's kind:\n"
    "  URDF (<robot> with <link>s)           -> our robot XML (y-up)\n"
    "  our world XML (<world>)               -> MJCF for MuJoCo (z-up), with its robots\n"
    "  our robot XML (<robot> with <body>s)  -> MJCF of the robot alone (no ground)\n"
    "\n"
    "  -o, --output OUT  file to write (required)\n"
    "  --mesh-as-box     URDF meshes (STL, OBJ) become their bounding box\n"
    "  --params FILE     parameters for MJCF (stepsize, contact defaults);\n"
    "                    --key=value overrides one, e.g. --stepsize=0.002\n"
    "  --help            this text\n"
    "Frames and what MJCF cannot carry: docs/convert.md.\n";

}  // namespace

InputKind DetectInputKind(const std::string& text, const std::string& file_name) {
  const UrdfLines lines = ReadXmlLines(text, file_name);
  if (lines.root_name == "world") return InputKind::kWorld;
  if (lines.root_name == "robot" && lines.has_bodies) return InputKind::kRobot;
  if (lines.root_name == "robot") return InputKind::kUrdf;
  throw Located(file_name, lines.robot,
                "cannot tell the direction: the root element is <" + lines.root_name +
                    "> (expected URDF <robot> with <link>s, or our <world> or <robot> with "
                    "<body>s)");
}

// The input as given, else a shipped world or robot found like every
// program finds its data (data_paths.h), so that `simpartner-convert
// gen4_flat.xml` works from any directory.
std::string FindInput(const std::string& name) {
  try {
    return FindDataFile(name, "model", {"models/worlds", "models/robots"});
  } catch (const DataFileNotFound& e) {
    throw ConvertError(e.diagnostics());
  }
}

ConvertOutcome Convert(const ConvertRequest& request) {
  const std::string input = FindInput(request.input);
  std::string text;
  try {
    if (!model::ReadFileFromDisk(input, &text)) throw Located(input, 0, "cannot read the file");
  } catch (const model::ModelFileError& error) {
    throw Located(input, 0, error.what());
  }
  ConvertOutcome outcome;
  outcome.kind = DetectInputKind(text, input);
  switch (outcome.kind) {
    case InputKind::kUrdf: {
      UrdfImportOptions options;
      options.mesh_as_box = request.mesh_as_box;
      UrdfImportResult result = ImportUrdf(text, input, options);
      outcome.text = result.robot_xml;
      outcome.notes = result.notes;
      break;
    }
    case InputKind::kWorld:
    case InputKind::kRobot: {
      model::World world;
      if (outcome.kind == InputKind::kWorld) {
        model::WorldLoadResult loaded = model::ParseWorld(text, input);
        if (!loaded.world) throw ModelError(loaded.diagnostics);
        world = *loaded.world;
      } else {
        model::RobotLoadResult loaded = model::ParseRobot(text, input);
        if (!loaded.robot) throw ModelError(loaded.diagnostics);
        world = WorldOfRobot(*loaded.robot);
      }
      MjcfExport result = ExportMjcf(world, request.params);
      outcome.text = result.xml;
      for (const std::string& left_out : result.not_carried)
        outcome.notes.push_back("not carried over: " + left_out);
      break;
    }
  }
  std::ofstream file(request.output, std::ios::binary | std::ios::trunc);
  if (!file) throw Error(request.output + ": cannot write the output file");
  file << outcome.text;
  file.close();
  if (!file) throw Error(request.output + ": writing the output file failed");
  return outcome;
}

int RunConvert(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  ConvertRequest request;
  CommandLine command_line;
  command_line.program = "simpartner-convert";
  std::vector<std::string> inputs;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&](const char* what) -> const std::string* {
      if (i + 1 >= args.size()) {
        err << "simpartner-convert: " << arg << " needs " << what << "\n" << kUsage;
        return nullptr;
      }
      return &args[++i];
    };
    if (arg == "--help" || arg == "-h") {
      out << kUsage;
      return 0;
    } else if (arg == "-o" || arg == "--output") {
      const std::string* v = value("the output file");
      if (v == nullptr) return 2;
      request.output = *v;
    } else if (arg == "--mesh-as-box") {
      request.mesh_as_box = true;
    } else if (arg == "--params") {
      const std::string* v = value("a parameters file");
      if (v == nullptr) return 2;
      command_line.params_file = *v;
      command_line.params_file_given = true;
    } else if (arg.rfind("--", 0) == 0 && arg.find('=') != std::string::npos) {
      const size_t eq = arg.find('=');
      command_line.overrides.emplace_back(arg.substr(2, eq - 2), arg.substr(eq + 1));
    } else if (arg.rfind("-", 0) == 0 && arg.size() > 1) {
      err << "simpartner-convert: unknown option '" << arg << "'\n" << kUsage;
      return 2;
    } else {
      inputs.push_back(arg);
    }
  }
  if (inputs.size() != 1 || request.output.empty()) {
    err << "simpartner-convert: " << (inputs.empty() ? "no input file" :
                                      inputs.size() > 1 ? "more than one input file" :
                                                          "no output file (-o OUT)")
        << "\n" << kUsage;
    return 2;
  }
  request.input = inputs.front();
  try {
    // The default parameters.txt only when the user names one: conversion
    // must not depend on the directory it runs in.
    if (command_line.params_file_given || !command_line.overrides.empty()) {
      if (!command_line.params_file_given) command_line.params_file.clear();
      request.params = LoadParameters(command_line);
    }
    const ConvertOutcome outcome = Convert(request);
    static const char* const kKinds[] = {"URDF -> robot XML", "robot XML -> MJCF",
                                         "world XML -> MJCF"};
    out << request.input << " -> " << request.output << " ("
        << kKinds[static_cast<int>(outcome.kind)] << ")\n";
    for (const std::string& note : outcome.notes) out << "  " << note << "\n";
    return 0;
  } catch (const Error& error) {
    err << error.what() << "\n";
    return 1;
  }
}

}  // namespace simpartner::convert
