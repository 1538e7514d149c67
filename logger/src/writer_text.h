// Column values the writer makes from message fields: the names of the
// model's kinds (Body.type, `Joint`.type ...), value lists, timestamps and
// VARCHAR text.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace simpartner::logger {

const char* GeometryName(int8_t kind);  // "BOX", ...; "UNKNOWN" for another number
const char* JointName(int8_t kind);     // "HINGE", ...
const char* SensorName(int8_t kind);    // "SCANNER", ...
const char* ActuatorName(int8_t kind);  // "ANGLE", ...

// "1,2.5,-3": shortest exact numbers, comma-separated.
std::string JoinValues(const std::vector<double>& values);
// FROM_UNIXTIME(s.micros): a DATETIME(6) expression for a UTC time in
// microseconds since the epoch.
std::string UtcFromMicros(int64_t micros);
// Text for a VARCHAR column from the logger's own messages (which may hold
// a path): valid UTF-8 of at most max_bytes bytes, other bytes as '?'.
std::string ColumnText(const std::string& text, size_t max_bytes);

}  // namespace simpartner::logger
