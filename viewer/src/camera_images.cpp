#include "simpartner/viewer/camera_images.h"

#include "simpartner/channels.h"
#include "simpartner/message_checks.h"

namespace simpartner::viewer {

CameraImages::CameraImages(lcm::LCM* lcm, BusSigning* signing, Reporter report, std::string shown)
    : signing_(signing), report_(std::move(report)), shown_(std::move(shown)) {
  // Two frames (colour and depth) are all an inset needs; older ones go.
  lcm->subscribeFunction(
         channels::kImage,
         +[](const lcm::ReceiveBuffer* buffer, const std::string&, CameraImages* self) {
           self->Offer(buffer->data, buffer->data_size);
         },
         this)
      ->setQueueCapacity(4);
}

void CameraImages::Offer(const void* data, size_t size) {
  image_t image;
  bool print = false;
  if (const auto refusal =
          DecodeSigned(channels::kImage, data, size, signing_, &image, &refused_, &print)) {
    if (print) report_(*refusal + "; ignored");
    return;
  }
  if (shown_.empty() || image.name != shown_ || image.format != image_t::FORMAT_RGB8) return;
  offered_ = std::move(image);
}

void CameraImages::Judge(const model_t& model, int64_t newest_state_step) {
  if (!offered_) return;
  if (offered_->simulation_id != model.simulation_id || offered_->name != shown_) {
    offered_.reset();  // another simulation's, or a camera no longer shown
    return;
  }
  if (const auto problem = CheckImage(*offered_, &model)) {
    if (bad_sizes_.Count(channels::kImage, problem->message))
      report_(std::string(channels::kImage) + ": image '" + offered_->name +
              "': " + problem->message + "; ignored");
    offered_.reset();
    return;
  }
  if (offered_->step > newest_state_step) return;
  newest_ = std::move(offered_);
  offered_.reset();
  ++version_;
}

void CameraImages::ShowNext(const model_t& model) {
  std::vector<std::string> cameras;
  for (const sensor_t& s : model.sensors)
    if (s.kind == sensor_t::KIND_CAMERA) cameras.push_back(s.name);
  size_t next = 0;  // from none: the first
  for (size_t k = 0; k < cameras.size(); ++k)
    if (cameras[k] == shown_) next = k + 1;
  shown_ = next < cameras.size() ? cameras[next] : "";
  offered_.reset();
  newest_.reset();
  ++version_;
}

const image_t* CameraImages::Newest(int64_t simulation_id) const {
  if (!newest_ || newest_->name != shown_ || newest_->simulation_id != simulation_id) return nullptr;
  return &*newest_;
}

}  // namespace simpartner::viewer
