#include "simpartner/client/image_store.h"

#include "simpartner/channels.h"
#include "simpartner/message_checks.h"

namespace simpartner::client {

void ImageStore::SetModel(std::shared_ptr<const model_t> model) {
  model_ = std::move(model);
  newest_.clear();
  held_.clear();
}

bool ImageStore::Offer(const void* data, size_t size, int64_t newest_state_step) {
  auto image = std::make_shared<image_t>();
  bool print = false;
  if (const auto refusal =
          DecodeFromBus(channels::kImage, data, size, image.get(), counter_, &print)) {
    if (print) report_(*refusal + "; ignored");
    return false;
  }
  if (!model_ || image->simulation_id != model_->simulation_id) return false;
  if (const auto problem = CheckImage(*image, model_.get())) {
    const std::string description = std::string(channels::kImage) + ": image of step " +
                                    std::to_string(image->step) + ": " + problem->message +
                                    "; ignored";
    if (counter_->Count(channels::kImage, description)) report_(description);
    return false;
  }
  const ImageKind kind =
      image->format == image_t::FORMAT_RGB8 ? ImageKind::kColour : ImageKind::kDepth;
  const Key key{image->camera, kind};
  if (image->step > newest_state_step) {
    held_[key] = std::move(image);
    return false;
  }
  newest_[key] = std::move(image);
  return true;
}

bool ImageStore::StateSeen(int64_t step) {
  bool kept = false;
  for (auto it = held_.begin(); it != held_.end();) {
    if (it->second->step > step) {
      ++it;
      continue;
    }
    newest_[it->first] = std::move(it->second);
    it = held_.erase(it);
    kept = true;
  }
  return kept;
}

std::optional<image_t> ImageStore::Latest(int camera, ImageKind kind) const {
  const auto it = newest_.find({camera, kind});
  if (it == newest_.end()) return std::nullopt;
  return *it->second;
}

int64_t ImageStore::LatestStep(int camera, ImageKind kind) const {
  const auto it = newest_.find({camera, kind});
  return it == newest_.end() ? -1 : it->second->step;
}

}  // namespace simpartner::client
