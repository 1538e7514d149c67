// One compared figure of a validation experiment: what was measured, the
// target (analytic or the real robot's), the tolerance and the verdict.
// The verdict is computed here from the numbers, never set by hand.
#pragma once

#include <string>

#include "simpartner/text.h"

namespace simpartner::validate {

enum class Comparison {
  kRelative,  // |measured - target| <= tolerance * |target|
  kAbsolute,  // |measured - target| <= tolerance
  kAtLeast,   // measured >= target (tolerance unused)
  kAtMost,    // measured <= target (tolerance unused)
};

struct Check {
  std::string label;        // what is compared, e.g. "error slope, dt = 0.001 s"
  double measured = 0.0;
  double target = 0.0;
  double tolerance = 0.0;   // a fraction for kRelative, in `unit` for kAbsolute
  Comparison comparison = Comparison::kAbsolute;
  std::string unit;         // "m/s", "N", "" (a ratio)
  bool pass = false;

  std::string MeasuredText() const;
  std::string TargetText() const;
  std::string ToleranceText() const;
};

// Constructors that compute the verdict. A non-finite measurement fails.
Check Relative(std::string label, double measured, double target, double fraction,
               std::string unit);
Check Absolute(std::string label, double measured, double target, double tolerance,
               std::string unit);
Check AtLeast(std::string label, double measured, double minimum, std::string unit);
Check AtMost(std::string label, double measured, double maximum, std::string unit);

// Numbers in checks and the report: FormatNumber (6 significant digits,
// "0.0049", "1.2e-13") and FormatFixed ("1354.1"), from simpartner/text.h.
using simpartner::FormatFixed;
using simpartner::FormatNumber;

}  // namespace simpartner::validate
