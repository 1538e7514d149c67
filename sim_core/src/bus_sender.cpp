#include "simpartner/sim/bus_sender.h"

#include <cerrno>
#include <cstring>
#include <utility>

namespace simpartner::sim {

BusSender::BusSender(lcm::LCM* lcm, BusSigning* signing)
    : lcm_(lcm), signing_(signing), thread_([this] { SendAll(); }) {}

BusSender::~BusSender() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  queued_.notify_one();
  thread_.join();
}

std::vector<uint8_t> BusSender::TakeSpare() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (spares_.empty()) return {};
  std::vector<uint8_t> bytes = std::move(spares_.back());
  spares_.pop_back();
  return bytes;
}

void BusSender::Queue(const char* channel, std::vector<uint8_t> bytes) {
  std::unique_lock<std::mutex> lock(mutex_);
  drained_.wait(lock, [&] { return queue_.size() < kMaxQueuedMessages; });
  queue_.push_back(Message{channel, std::move(bytes)});
  ++messages_queued_;
  if (sleeping_ || queue_.size() >= kWakeAt) Wake(&lock);
}

void BusSender::Kick() {
  std::unique_lock<std::mutex> lock(mutex_);
  if (waiting_ && !queue_.empty()) Wake(&lock);
}

void BusSender::Flush() {
  std::unique_lock<std::mutex> lock(mutex_);
  const uint64_t target = messages_queued_;
  Wake(&lock);
  lock.lock();
  drained_.wait(lock, [&] { return messages_done_ >= target; });
}

void BusSender::Wake(std::unique_lock<std::mutex>* lock) {
  wake_ = true;
  lock->unlock();
  queued_.notify_one();
}

std::vector<BusSender::Outcome> BusSender::TakeOutcomes() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(outcomes_, {});
}

bool BusSender::WaitForWork(std::unique_lock<std::mutex>* lock, bool sent_before) {
  const auto woken = [&] { return wake_ || stop_; };
  waiting_ = true;
  // After a round that sent something, more is likely: look again after
  // kPollPeriod. With nothing to send, sleep until woken.
  if (sent_before) queued_.wait_for(*lock, kPollPeriod, woken);
  // Woken with nothing queued (a Flush with nothing left to send): wait
  // again; only a stop ends the thread.
  while (queue_.empty() && !stop_) {
    wake_ = false;
    sleeping_ = true;
    queued_.wait(*lock, woken);
    sleeping_ = false;
  }
  waiting_ = wake_ = false;
  return !queue_.empty();
}

void BusSender::SendAll() {
  std::unique_lock<std::mutex> lock(mutex_);
  bool sent = false;
  while (WaitForWork(&lock, sent)) {
    std::deque<Message> batch;
    batch.swap(queue_);
    lock.unlock();
    // On stop, what is queued still goes out: the last SIM_STATUS says
    // the run stopped.
    for (const Message& message : batch) Publish(message);
    lock.lock();
    messages_done_ += batch.size();
    for (Message& message : batch) {
      if (spares_.size() == kMaxSpares) break;
      spares_.push_back(std::move(message.bytes));
    }
    sent = true;
    drained_.notify_all();
  }
}

void BusSender::Publish(const Message& message) {
  const std::vector<uint8_t>* bytes = &message.bytes;
  std::vector<uint8_t> signed_bytes;
  if (signing_ != nullptr) {
    signed_bytes = signing_->Sign(message.channel, bytes->data(), bytes->size());
    bytes = &signed_bytes;
  }
  const int status =
      lcm_->publish(message.channel, bytes->data(), static_cast<unsigned>(bytes->size()));
  if (status == 0 && !failing_) return;
  Outcome outcome{message.channel, status == 0, status == 0 ? "" : std::strerror(errno)};
  failing_ = status != 0;
  std::lock_guard<std::mutex> lock(mutex_);
  outcomes_.push_back(std::move(outcome));
}

}  // namespace simpartner::sim
