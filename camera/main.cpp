// simpartner-camera: parse flags, load parameters (for lcmUrl), render the
// cameras of whatever simulation runs on the bus.
#include <iostream>

#include "simpartner/camera/app.h"

int main(int argc, char** argv) {
  using namespace simpartner;
  CommandLine command_line;
  if (const auto done = ReadCommandLine(camera::CameraCommandLine(), {argv + 1, argv + argc},
                                        std::cout, std::cerr, &command_line))
    return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, params, std::cout)) return 0;
    const camera::CameraOptions options = camera::MakeCameraOptions(command_line, params);
    return camera::RunCamera(options, std::cout, std::cerr);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostics().Format() << "\nsimpartner-camera: nothing started\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "simpartner-camera: " << e.what() << "\n";
    return 1;
  }
}
