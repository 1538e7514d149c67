// Waiting in a test for something another process does, without a bus (a
// bus listener waits with BusListener::Until, which keeps receiving).
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>

namespace simpartner::test_support {

// Checks `condition` every `poll` until it holds or `seconds` have passed;
// returns its last value.
bool WaitFor(const std::function<bool()>& condition, double seconds,
             std::chrono::milliseconds poll = std::chrono::milliseconds(50));

// Until the file at `path` (a process's log) holds `text`.
bool WaitForText(const std::filesystem::path& path, const std::string& text, double seconds);

}  // namespace simpartner::test_support
