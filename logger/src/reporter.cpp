#include "simpartner/logger/reporter.h"

namespace simpartner::logger {

void Reporter::Say(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  *out_ << program_ << ": " << line << std::endl;
}

void Reporter::SayLimited(const std::string& key, const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (const auto said = limited_.Pass(key, line, Clock::now()))
    *out_ << program_ << ": " << *said << std::endl;
}

}  // namespace simpartner::logger
