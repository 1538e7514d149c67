// The camera images on the bus (SIM_IMAGE, from simpartner-camera) for the
// viewer's inset: the newest colour image of the camera shown, chosen by
// name (--camera-image) or in turn with a key. Depth images and images of
// other simulations or cameras are not kept. Decoded like every message
// (bus_decode.h, signed when the bus is), then checked against the model's
// camera (CheckImage) and shown only once the viewer has a state of its
// step: the camera renders states the sim published, so an image ahead
// of them (a forged one, with no camera running) waits and is never
// shown. Refused ones are reported through the viewer's reporter, the
// first of a channel and then every 1000th.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "simpartner/bus_decode.h"
#include "simpartner/image_t.hpp"
#include "simpartner/model_t.hpp"

namespace simpartner::viewer {

class CameraImages {
 public:
  using Reporter = std::function<void(const std::string&)>;
  // lcm and signing (null: an unsigned bus) outlive this.
  CameraImages(lcm::LCM* lcm, BusSigning* signing, Reporter report, std::string shown = "");
  CameraImages(const CameraImages&) = delete;
  CameraImages& operator=(const CameraImages&) = delete;

  // The next camera of `model` after the one shown, then none, then the first.
  void ShowNext(const model_t& model);
  const std::string& shown() const { return shown_; }
  // Takes the newest image offered when it fits `model`'s camera (else
  // reports it) and the viewer has a state of its step (at most
  // newest_state_step; else it waits for one).
  void Judge(const model_t& model, int64_t newest_state_step);
  // The newest colour image of the camera shown that Judge took, of
  // simulation `simulation_id`.
  const image_t* Newest(int64_t simulation_id) const;
  // Changes with every image kept, so the viewer knows to draw again.
  int64_t version() const { return version_; }

  // What the subscription does with one datagram (public for the tests).
  void Offer(const void* data, size_t size);

 private:
  BusSigning* signing_;
  Reporter report_;
  std::string shown_;
  BadMessageCounter refused_;    // that do not decode or open
  BadMessageCounter bad_sizes_;  // decoded, but not what the camera sends
  std::optional<image_t> offered_;  // the newest from the bus, not yet judged
  std::optional<image_t> newest_;
  int64_t version_ = 0;
};

}  // namespace simpartner::viewer
