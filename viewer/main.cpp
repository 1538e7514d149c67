// simpartner-viewer: parse flags, load parameters (for lcmUrl), run the window.
#include <iostream>

#include "simpartner/viewer/app.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(viewer::ViewerCommandLine(), {argv + 1, argv + argc},
                                        std::cout, std::cerr, &command_line))
    return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
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
