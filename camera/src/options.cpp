#include "simpartner/camera/options.h"

namespace simpartner::camera {

CommandLineSpec CameraCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-camera";
  spec.summary =
      "Renders the camera sensors of whatever simulation runs on the bus (sensor type Camera in\n"
      "the robot file) and publishes their images on SIM_IMAGE (image_t): colour, and depth in\n"
      "metres or millimetres where the camera has it. It learns the model from SIM_MODEL like the\n"
      "viewer (asking with SIM_MODEL_REQUEST when it starts late or the sim restarts) and renders\n"
      "each camera at its rate in sim time, from the SIM_STATE of the step the image is stamped\n"
      "with. It draws offscreen with OpenGL: it needs an X display (a real GPU, or Xvfb with\n"
      "Mesa's llvmpipe). docs/sensors-camera.md describes the images.";
  spec.options = {
      Number("quit-after", "S", "exit after this many seconds and print frame figures")
          .Range(0, 1e9),
      Text("save", "DIR", "when it exits, write each camera's last colour frame as DIR/NAME.png"),
  };
  spec.parameters = ParameterUse{{parameter_sections::kTransport}};
  return spec;
}

CameraOptions MakeCameraOptions(const CommandLine& command_line, const Parameters& params) {
  CameraOptions o;
  o.lcm_url = params.lcmUrl;
  o.quit_after = command_line.Number("quit-after", o.quit_after);
  o.save_dir = command_line.Text("save");
  return o;
}

}  // namespace simpartner::camera
