#include "writer_text.h"

#include <cstdio>

#include "simpartner/logger/receiver.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/sensor_kinds.h"
#include "simpartner/text.h"

namespace simpartner::logger {

const char* GeometryName(int8_t kind) {
  switch (kind) {
    case 0: return "NONE";
    case 1: return "BOX";
    case 2: return "SPHERE";
    case 3: return "CYLINDER";
    case 4: return "CAPSULE";
  }
  return "UNKNOWN";
}

const char* JointName(int8_t kind) {
  switch (kind) {
    case 0: return "FIXED";
    case 1: return "HINGE";
    case 2: return "SLIDER";
    case 3: return "BALL";
    case 4: return "UNIVERSAL";
    case 5: return "HINGE2";
  }
  return "UNKNOWN";
}

const char* SensorName(int8_t kind) { return SpellSensorKind(kind).database; }

const char* ActuatorName(int8_t kind) {
  switch (kind) {
    case 0: return "JOINT_VELOCITY";
    case 1: return "ANGLE";
    case 2: return "LINEAR_MOTOR";
  }
  return "UNKNOWN";
}

std::string JoinValues(const std::vector<double>& values) {
  std::string out;
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) out.push_back(',');
    AppendDouble(&out, values[i]);
  }
  return out;
}

std::string UtcFromMicros(int64_t micros) {
  char frac[8];
  std::snprintf(frac, sizeof frac, "%06lld", static_cast<long long>(micros % 1000000));
  return "FROM_UNIXTIME(" + std::to_string(micros / 1000000) + "." + frac + ")";
}

std::string ColumnText(const std::string& text, size_t max_bytes) {
  if (FitsText(text, max_bytes)) return text;
  std::string out;
  for (const char c : text) {
    if (out.size() >= max_bytes) break;
    const unsigned char u = static_cast<unsigned char>(c);
    out.push_back(u >= 0x20 && u < 0x80 ? c : '?');
  }
  return out;
}

}  // namespace simpartner::logger
