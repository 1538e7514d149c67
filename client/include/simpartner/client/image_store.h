// The newest camera images (image_t on SIM_IMAGE) a Client keeps: per
// camera of the model, the newest colour and the newest depth image. An
// image is kept only when it decodes and passes CheckImage (message_checks.h: a
// camera of this simulation, its format, its declared resolution, its byte
// count); any other is dropped with a line naming the channel, the field
// and its value (the first of each kind, then every 1000th). An image of
// a step the client has not yet seen a state of is held (the newest per
// camera and kind) until that state comes: the camera renders states the
// sim has published, so one stamped ahead of them (the audit's step 1e12)
// is never handed out. Not thread-safe: the Client calls it under its lock.
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
  // it when it fits and its step is at most newest_state_step (else holds
  // it); true when kept. Images of another simulation are dropped quietly
  // (a second sim on the bus is no fault).
  bool Offer(const void* data, size_t size, int64_t newest_state_step);
  // A state of `step` came: the images held for it are kept; true when any.
  bool StateSeen(int64_t step);

  // The newest image of sensor `camera` (index into model_t.sensors).
  std::optional<image_t> Latest(int camera, ImageKind kind) const;
  // Step of that image, -1 before the first.
  int64_t LatestStep(int camera, ImageKind kind) const;

 private:
  BadMessageCounter* counter_;
  Reporter report_;
  std::shared_ptr<const model_t> model_;
  using Key = std::pair<int, ImageKind>;
  std::map<Key, std::shared_ptr<const image_t>> newest_;
  std::map<Key, std::shared_ptr<const image_t>> held_;  // ahead of the states seen
};

}  // namespace simpartner::client
