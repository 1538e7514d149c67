// simpartner-cmd: one command to the sim from a shell (see RunCmd); camera
// images go to PNG files through common/png_image.h.
#include <iostream>

#include "simpartner/client/cmd.h"
#include "simpartner/png_image.h"

int main(int argc, char** argv) {
  return simpartner::client::RunCmd(std::vector<std::string>(argv + 1, argv + argc), std::cout,
                                    std::cerr, simpartner::WriteImagePng);
}
