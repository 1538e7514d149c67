// simpartner-viewer: parse flags, load parameters (for lcmUrl), run the window.
#include <iostream>

#include "simpartner/viewer/app.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  try {
    const CommandLine command_line = ParseCommandLine(argc, argv, viewer::ViewerFlags());
    if (command_line.Has("help")) {
      std::cout << FormatUsage("simpartner-viewer", viewer::ViewerSummary(), viewer::ViewerFlags(),
                               {parameter_sections::kTransport});
      return 0;
    }
    const Parameters params = LoadParameters(command_line);
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    const viewer::ViewerOptions options = viewer::MakeViewerOptions(command_line, params);
    return viewer::RunViewer(options, std::cout, std::cerr);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostics().Format() << "\nsimpartner-viewer: nothing started\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simpartner-viewer: " << e.what() << "\n";
    return 1;
  }
}
