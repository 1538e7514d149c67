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

CommandLineSpec ConvertCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-convert";
  spec.summary =
      "Converts a robot model; the direction comes from IN's kind:\n"
      "  URDF (<robot> with <link>s)           -> our robot XML (y-up)\n"
      "  our world XML (<world>)               -> MJCF for MuJoCo (z-up), with its robots\n"
      "  our robot XML (<robot> with <body>s)  -> MJCF of the robot alone (no ground)\n"
      "An IN not found as given is looked for among the shipped models/worlds and models/robots.\n"
      "Frames and what MJCF cannot carry: docs/convert.md.";
  spec.options = {Text("output", "OUT", "file to write (required)").Short('o'),
                  Switch("mesh-as-box", "URDF meshes (STL, OBJ) become their bounding box")};
  spec.required = {"output"};
  spec.positionals = {Positional{"IN"}};
  // MJCF takes the step size and the contact defaults; the conversion does
  // not depend on the directory it runs in, so no default parameters file.
  spec.parameters = ParameterUse{{parameter_sections::kStepping, parameter_sections::kContact}, false};
  return spec;
}

int RunConvert(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CommandLine command_line;
  if (const auto done = ReadCommandLine(ConvertCommandLine(), args, out, err, &command_line))
    return *done;
  ConvertRequest request;
  request.input = command_line.positional().front();
  request.output = command_line.Text("output");
  request.mesh_as_box = command_line.Has("mesh-as-box");
  try {
    request.params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, request.params, out)) return 0;
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
