#include "simpartner/validate/check.h"

#include <cmath>
#include <cstdio>
#include <utility>

namespace simpartner::validate {
namespace {

std::string WithUnit(const std::string& number, const std::string& unit) {
  return unit.empty() ? number : number + " " + unit;
}

Check Make(std::string label, double measured, double target, double tolerance,
           Comparison comparison, std::string unit) {
  Check c;
  c.label = std::move(label);
  c.measured = measured;
  c.target = target;
  c.tolerance = tolerance;
  c.comparison = comparison;
  c.unit = std::move(unit);
  const double error = std::abs(measured - target);
  switch (comparison) {
    case Comparison::kRelative: c.pass = error <= tolerance * std::abs(target); break;
    case Comparison::kAbsolute: c.pass = error <= tolerance; break;
    case Comparison::kAtLeast: c.pass = measured >= target; break;
    case Comparison::kAtMost: c.pass = measured <= target; break;
  }
  c.pass = c.pass && std::isfinite(measured);
  return c;
}

}  // namespace

std::string Check::MeasuredText() const { return WithUnit(FormatNumber(measured), unit); }

std::string Check::TargetText() const {
  switch (comparison) {
    case Comparison::kAtLeast: return ">= " + WithUnit(FormatNumber(target), unit);
    case Comparison::kAtMost: return "<= " + WithUnit(FormatNumber(target), unit);
    default: return WithUnit(FormatNumber(target), unit);
  }
}

std::string Check::ToleranceText() const {
  switch (comparison) {
    case Comparison::kRelative: return "±" + FormatNumber(tolerance * 100.0) + " %";
    case Comparison::kAbsolute: return "±" + WithUnit(FormatNumber(tolerance), unit);
    default: return "-";
  }
}

Check Relative(std::string label, double measured, double target, double fraction,
               std::string unit) {
  return Make(std::move(label), measured, target, fraction, Comparison::kRelative,
              std::move(unit));
}

Check Absolute(std::string label, double measured, double target, double tolerance,
               std::string unit) {
  return Make(std::move(label), measured, target, tolerance, Comparison::kAbsolute,
              std::move(unit));
}

Check AtLeast(std::string label, double measured, double minimum, std::string unit) {
  return Make(std::move(label), measured, minimum, 0.0, Comparison::kAtLeast, std::move(unit));
}

Check AtMost(std::string label, double measured, double maximum, std::string unit) {
  return Make(std::move(label), measured, maximum, 0.0, Comparison::kAtMost, std::move(unit));
}

}  // namespace simpartner::validate
