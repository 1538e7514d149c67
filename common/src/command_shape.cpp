#include "simpartner/command_shape.h"

#include "simpartner/actuator_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/sensor_t.hpp"

namespace simpartner {
namespace {

// Per-axis groups of a SET/HOLD/STOPS, and the gains after them.
struct Layout {
  std::vector<std::string> groups;  // names of the per-axis groups
  bool stops = false;               // one group of lo, hi pairs
  bool gains = false;               // P, I, D after the groups
  bool valid = false;
};

Layout ActuatorLayout(const CommandTargetShape& target, int action) {
  Layout layout;
  switch (action) {
    case command_t::ACTION_SET:
      layout.groups.push_back("fmax");
      if (target.kind == actuator_t::KIND_ANGLE) {
        layout.groups.push_back("angle");
        layout.gains = true;
      } else {
        layout.groups.push_back("vel");
      }
      layout.valid = true;
      break;
    case command_t::ACTION_HOLD:
      layout.groups.push_back("fmax");
      layout.valid = true;
      break;
    case command_t::ACTION_SET_STOPS:
      layout.stops = true;
      layout.valid = true;
      break;
    default:
      break;
  }
  return layout;
}

int FormCount(const Layout& layout, int places) {
  const int per_place = layout.stops ? 2 : static_cast<int>(layout.groups.size());
  return places * per_place + (layout.gains ? 3 : 0);
}

}  // namespace

std::vector<int> AcceptedValueCounts(const CommandTargetShape& target, int action) {
  if (target.is_sensor) {
    // simpartner-camera renders a camera; the sim takes no command for it.
    if (target.kind == sensor_t::KIND_CAMERA) return {};
    switch (action) {
      case command_t::ACTION_READ: return {0};
      case command_t::ACTION_SET:
        if (target.kind == sensor_t::KIND_ECHO) return {-1};
        return {};
      case command_t::ACTION_SENSOR_PARAMS:
        if (target.kind == sensor_t::KIND_SCANNER) return {1, 4};
        return {1};
      default: return {};
    }
  }
  const Layout layout = ActuatorLayout(target, action);
  if (!layout.valid) return {};
  std::vector<int> counts;
  if (action == command_t::ACTION_HOLD) counts.push_back(0);  // force limits are optional
  counts.push_back(FormCount(layout, 3));
  const int short_form = FormCount(layout, target.num_axes);
  if (short_form != counts.back()) counts.push_back(short_form);
  return counts;
}

std::vector<std::string> ValueNames(const CommandTargetShape& target, int action, int count) {
  std::vector<std::string> names;
  if (target.is_sensor) {
    if (action == command_t::ACTION_SENSOR_PARAMS) {
      names = {"rate"};
      if (count == 4) names = {"rate", "rays", "halfSpan", "range"};
    }
    return names;
  }
  const Layout layout = ActuatorLayout(target, action);
  if (!layout.valid || count <= 0) return names;
  const bool slot_form = count == FormCount(layout, 3);
  const int places = slot_form ? 3 : target.num_axes;
  const char* slots[3] = {"x", "y", "z"};
  auto place = [&](int p) -> std::string {
    if (slot_form) return std::string("_") + slots[p];
    return places > 1 ? std::to_string(p + 1) : "";
  };
  if (layout.stops) {
    for (int p = 0; p < places; ++p) {
      names.push_back("lo" + place(p));
      names.push_back("hi" + place(p));
    }
  } else {
    for (const std::string& group : layout.groups)
      for (int p = 0; p < places; ++p) names.push_back(group + place(p));
  }
  if (layout.gains) {
    names.push_back("P");
    names.push_back("I");
    names.push_back("D");
  }
  return names;
}

std::string DescribeValueForms(const CommandTargetShape& target, int action) {
  const std::vector<int> counts = AcceptedValueCounts(target, action);
  std::string out;
  for (int count : counts) {
    if (!out.empty()) out += " or ";
    if (count < 0) {
      out += "any text (echoed)";
      continue;
    }
    if (count == 0) {
      out += "no values";
      continue;
    }
    std::string joined;
    for (const std::string& name : ValueNames(target, action, count))
      joined += (joined.empty() ? "" : ",") + name;
    out += joined + " (" + std::to_string(count) + ")";
  }
  return out;
}

std::string CheckValueCount(const CommandTargetShape& target, int action, int count) {
  const std::vector<int> counts = AcceptedValueCounts(target, action);
  if (counts.empty() && target.is_sensor && target.kind == sensor_t::KIND_CAMERA)
    return "a camera takes no command: simpartner-camera renders it (images on SIM_IMAGE)";
  if (counts.empty())
    return std::string("action '") + ActionName(action) + "' does not apply to " +
           (target.is_sensor ? "this sensor" : "an actuator");
  for (int accepted : counts)
    if (accepted < 0 || accepted == count) return "";
  std::string expected;
  for (size_t k = 0; k < counts.size(); ++k) {
    if (k) expected += k + 1 == counts.size() ? " or " : ", ";
    expected += std::to_string(counts[k]);
  }
  return "expected " + expected + " values (" + DescribeValueForms(target, action) + "), got " +
         std::to_string(count);
}

const std::vector<ActionSpelling>& ActionSpellings() {
  static const std::vector<ActionSpelling> kSpellings = {
      {command_t::ACTION_SET, "set", "set", "SET"},
      {command_t::ACTION_HOLD, "hold", "hold", "HOLD"},
      {command_t::ACTION_SET_STOPS, "stops", "stops", "SET_STOPS"},
      {command_t::ACTION_SENSOR_PARAMS, "params", "sensorParams", "SENSOR_PARAMS"},
      {command_t::ACTION_READ, "read", "read", "READ"},
  };
  return kSpellings;
}

const ActionSpelling& SpellAction(int action) {
  static const ActionSpelling kUnknown = {-1, "unknown action", "unknown action", "UNKNOWN"};
  for (const ActionSpelling& s : ActionSpellings())
    if (s.action == action) return s;
  return kUnknown;
}

int ActionOfSequenceElement(const std::string& element) {
  for (const ActionSpelling& s : ActionSpellings())
    if (element == s.sequence_element) return s.action;
  return -1;
}

}  // namespace simpartner
