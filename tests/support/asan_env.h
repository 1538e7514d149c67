// The environment a test gives a child process it starts under the sanitized
// build, in one place for the process tests that start the viewer or teleop
// (their SDL/GL libraries are loaded by LD_PRELOAD before ASan's runtime).
#pragma once

#include <cstdlib>
#include <string>

namespace simpartner::test_support {

// The caller's ASAN_OPTIONS, and no complaint that the preloaded library
// (tests/viewer/keep_libraries_loaded.c) comes before ASan's runtime.
inline std::string AsanOptions() {
  const char* given = std::getenv("ASAN_OPTIONS");
  return (given != nullptr && *given != '\0' ? std::string(given) + ":" : std::string()) +
         "verify_asan_link_order=0";
}

}  // namespace simpartner::test_support
