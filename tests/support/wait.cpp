#include "wait.h"

#include <thread>

#include "text_file.h"

namespace simpartner::test_support {

bool WaitFor(const std::function<bool()>& condition, double seconds, std::chrono::milliseconds poll) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(poll);
  }
  return condition();
}

bool WaitForText(const std::filesystem::path& path, const std::string& text, double seconds) {
  return WaitFor([&] { return ReadText(path).find(text) != std::string::npos; }, seconds,
                 std::chrono::milliseconds(20));
}

}  // namespace simpartner::test_support
