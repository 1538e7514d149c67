// The newest camera images (image_t on SIM_IMAGE) a Client keeps: per
// camera of the model, the newest colour and the newest depth image. An
// image is kept only when it decodes and passes CheckImage (message_checks.h: a
// camera of this simulation, its format, its declared resolution, its byte
// count); any other is dropped with a line naming the channel, the field
// and its value (the first of each kind, then every 1000th). Not
// thread-safe: the Client calls it under its lock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "simpartner/bus_decode.h"
#include "simpartner/image_t.hpp"
#include "simpartner/model_t.hpp"

namespace simpartner::client {

using simpartner::image_t;

// Which image of a camera: colour (FORMAT_RGB8) or depth (FORMAT_DEPTH_*).
enum class ImageKind { kColour, kDepth };

class ImageStore {
 public:
  using Reporter = std::function<void(const std::string&)>;
  // Dropped images are counted in `counter` (the Client's, which outlives
  // this) and the lines to print go to `report`.
  ImageStore(BadMessageCounter* counter, Reporter report)
      : counter_(counter), report_(std::move(report)) {}

  // The model images are checked against; drops the images kept. Null:
  // no model, every image is dropped quietly.
  void SetModel(std::shared_ptr<const model_t> model);

  // Decodes one SIM_IMAGE message (already opened: bus_decode.h) and keeps
  // it when it fits; true when kept. Images of another simulation are
  // dropped quietly (a second sim on the bus is no fault).
  bool Offer(const void* data, size_t size);

  // The newest image of sensor `camera` (index into model_t.sensors).
  std::optional<image_t> Latest(int camera, ImageKind kind) const;
  // Step of that image, -1 before the first.
  int64_t LatestStep(int camera, ImageKind kind) const;

 private:
  BadMessageCounter* counter_;
  Reporter report_;
  std::shared_ptr<const model_t> model_;
  std::map<std::pair<int, ImageKind>, std::shared_ptr<const image_t>> newest_;
};

}  // namespace simpartner::client
