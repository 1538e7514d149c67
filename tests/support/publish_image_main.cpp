// sp_test_publish_image URL CAMERA SECONDS: stands in for simpartner-camera
// in the Python test (no display needed). It learns the model from the
// bus, then for SECONDS publishes on SIM_IMAGE, stamped with the newest
// state's step, a colour image of camera CAMERA at its declared
// resolution, red = column % 256, green = row % 256, blue = 7, and, when the
// camera declares depth, a depth image of 1 m + 1 mm per column (uint16
// millimetres or float32 metres, as it declares). It signs as the camera
// does (SIMPARTNER_BUS_KEY).
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>

#include "simpartner/bus_decode.h"
#include "simpartner/bus_signing.h"
#include "simpartner/channels.h"
#include "simpartner/image_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/model_request_t.hpp"
#include "simpartner/state_t.hpp"

namespace {

using namespace simpartner;

struct Heard {
  BusSigning* signer = nullptr;
  std::optional<model_t> model;
  std::optional<state_t> state;
};

image_t Frame(const model_t& model, const sensor_t& camera, const state_t& state, int format) {
  image_t image{};
  image.simulation_id = model.simulation_id;
  image.step = state.step;
  image.sim_time = state.sim_time;
  image.camera = camera.id;
  image.name = camera.name;
  image.robot = model.robots.at(static_cast<size_t>(camera.robot)).name;
  image.width = static_cast<int32_t>(camera.params.at(0));
  image.height = static_cast<int32_t>(camera.params.at(1));
  image.format = static_cast<int8_t>(format);
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (format == image_t::FORMAT_RGB8) {
    image.data.resize(3 * pixels);
    for (size_t i = 0; i < pixels; ++i) {
      image.data[3 * i] = static_cast<uint8_t>(i % static_cast<size_t>(image.width) % 256);
      image.data[3 * i + 1] = static_cast<uint8_t>(i / static_cast<size_t>(image.width) % 256);
      image.data[3 * i + 2] = 7;
    }
  } else {
    const size_t bytes = format == image_t::FORMAT_DEPTH_F32 ? 4 : 2;
    image.data.resize(bytes * pixels);
    for (size_t i = 0; i < pixels; ++i) {
      const size_t column = i % static_cast<size_t>(image.width);
      if (bytes == 4) {
        const float metres = 1.0f + static_cast<float>(column) / 1000.0f;
        std::memcpy(image.data.data() + 4 * i, &metres, 4);
      } else {
        const uint16_t millimetres = static_cast<uint16_t>(1000 + column);
        std::memcpy(image.data.data() + 2 * i, &millimetres, 2);
      }
    }
  }
  image.num_bytes = static_cast<int32_t>(image.data.size());
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: sp_test_publish_image URL CAMERA SECONDS\n";
    return 2;
  }
  lcm::LCM lcm(argv[1]);
  if (!lcm.good()) return 1;
  std::optional<BusSigning> signing = BusSigning::FromEnvironment({});
  BusSigning* const signer = signing ? &*signing : nullptr;
  Heard heard;
  heard.signer = signer;
  lcm.subscribeFunction(
      channels::kModel,
      +[](const lcm::ReceiveBuffer* b, const std::string& c, Heard* h) {
        model_t m;
        if (!DecodeSigned(c, b->data, b->data_size, h->signer, &m, nullptr)) h->model = m;
      },
      &heard);
  lcm.subscribeFunction(
      channels::kState,
      +[](const lcm::ReceiveBuffer* b, const std::string& c, Heard* h) {
        state_t s;
        if (!DecodeSigned(c, b->data, b->data_size, h->signer, &s, nullptr)) h->state = s;
      },
      &heard);
  using Clock = std::chrono::steady_clock;
  const auto end = Clock::now() + std::chrono::duration<double>(std::stod(argv[3]));
  auto next = Clock::now();
  while (Clock::now() < end) {
    lcm.handleTimeout(20);
    if (Clock::now() < next) continue;
    next = Clock::now() + std::chrono::milliseconds(100);
    if (!heard.model) {
      model_request_t request{};
      request.sender = "sp_test_publish_image";
      PublishSigned(&lcm, channels::kModelRequest, request, signer);
      continue;
    }
    if (!heard.state || heard.state->simulation_id != heard.model->simulation_id) continue;
    for (const sensor_t& s : heard.model->sensors) {
      if (s.name != argv[2] || s.kind != sensor_t::KIND_CAMERA) continue;
      const image_t colour = Frame(*heard.model, s, *heard.state, image_t::FORMAT_RGB8);
      PublishSigned(&lcm, channels::kImage, colour, signer);
      const int depth = static_cast<int>(s.params.at(5));
      if (depth != 0) {
        const image_t image = Frame(*heard.model, s, *heard.state, depth);
        PublishSigned(&lcm, channels::kImage, image, signer);
      }
    }
  }
  return 0;
}
