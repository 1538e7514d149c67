// The CSV of logged sensor readings (SensorReading): the columns of each
// kind come from the one table of kinds (sensor_kinds.h), from the type and
// parameters the logger stored in Sensor.
#include <cppconn/exception.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <memory>
#include <ostream>

#include "simpartner/csv_field.h"
#include "simpartner/logger/export.h"
#include "simpartner/logger/simulations.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/sensor_kinds.h"
#include "simpartner/text.h"

namespace simpartner::logger {
namespace {

// Comma-separated numbers as the logger writes them (NULL: not finite).
std::vector<double> SplitValues(const std::string& text) {
  std::vector<double> values;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    double v = std::numeric_limits<double>::quiet_NaN();
    std::from_chars(text.data() + start, text.data() + end, v);  // "NULL" stays NaN
    values.push_back(v);
    start = end + 1;
  }
  return values;
}

// The sensor as far as its readings' layout goes: its kind and parameters.
sensor_t StoredSensor(const std::string& type, const std::string& params) {
  sensor_t s{};
  s.kind = -1;
  for (const SensorKindSpelling& k : SensorKindSpellings())
    if (type == k.database) s.kind = static_cast<int8_t>(k.kind);
  s.params = SplitValues(params);
  s.num_params = static_cast<int32_t>(s.params.size());
  return s;
}

// One logged reading, with what is needed to name its values.
struct LoggedReading {
  double time = 0;
  int64_t step = 0;
  std::string sensor;
  sensor_t layout;
  std::vector<double> values;
  std::string text;
};

void AppendStart(const LoggedReading& r, std::string* line) {
  line->clear();
  AppendDouble(line, r.time);
  line->push_back(',');
  AppendInt(line, r.step);
  *line += "," + CsvField(r.sensor);
}

bool Layered(const sensor_t& layout) {
  return layout.kind == sensor_t::KIND_SCANNER || layout.kind == sensor_t::KIND_LIDAR;
}

// The header of the wide layout of one sensor.
std::string WideHeader(const sensor_t& layout) {
  std::string header = "time_s,step,sensor";
  if (Layered(layout)) header += ",layer";
  for (const std::string& c : ReadingColumns(layout)) header += "," + c;
  if (layout.kind == sensor_t::KIND_ECHO) header += ",text";
  return header;
}

// Wide: one line per reading (per layer of a scanner or lidar, after its
// layer number), the values under the kind's names.
uint64_t WriteWide(const LoggedReading& r, bool* header_written, std::ostream& out) {
  const ReadingShape shape = ShapeOfReading(r.layout);
  const bool layered = Layered(r.layout);
  if (!*header_written) {
    out << WideHeader(r.layout) << "\n";
    *header_written = true;
  }
  std::string line;
  const size_t columns = static_cast<size_t>(std::max(shape.columns, 0));
  const size_t rows = r.layout.kind == sensor_t::KIND_ECHO ? 1 : static_cast<size_t>(shape.rows);
  for (size_t row = 0; row < rows; ++row) {
    AppendStart(r, &line);
    if (layered) line += "," + std::to_string(row);
    for (size_t k = 0; k < columns; ++k) {
      const size_t i = row * columns + k;
      line.push_back(',');
      AppendDouble(&line, i < r.values.size() ? r.values[i] : std::nan(""));
    }
    if (r.layout.kind == sensor_t::KIND_ECHO) line += "," + CsvField(r.text);
    out << line << "\n";
  }
  return rows;
}

// Long: one line per value, named by its kind's column (and layer), so
// sensors of every kind share one header.
uint64_t WriteLong(const LoggedReading& r, std::ostream& out) {
  const std::vector<std::string> names = ReadingColumns(r.layout);
  const char* kind = SpellSensorKind(r.layout.kind).word;
  std::string line;
  uint64_t count = 0;
  if (r.layout.kind == sensor_t::KIND_ECHO) {
    AppendStart(r, &line);
    out << line << "," << kind << ",0,text," << CsvField(r.text) << "\n";
    return 1;
  }
  for (size_t i = 0; i < r.values.size(); ++i) {
    AppendStart(r, &line);
    const size_t row = names.empty() ? 0 : i / names.size();
    const std::string name = names.empty() ? "value_" + std::to_string(i) : names[i % names.size()];
    line += std::string(",") + kind + "," + std::to_string(row) + "," + name + ",";
    AppendDouble(&line, r.values[i]);
    out << line << "\n";
    ++count;
  }
  return count;
}

std::string ReadingsSql(uint32_t simulation, const ReadingsRequest& request) {
  std::string sql =
      "SELECT r.simulationTime, r.step, s.name, s.type, s.params, r.vals, r.text "
      "FROM SensorReading r JOIN Sensor s ON s.sensorID = r.sensorID WHERE r.simulationID = " +
      std::to_string(simulation);
  if (!request.sensor.empty()) sql += " AND s.name = " + Quoted(request.sensor);
  if (std::isfinite(request.from))
    sql += " AND r.simulationTime >= " + ShortestNumber(request.from);
  if (std::isfinite(request.to)) sql += " AND r.simulationTime <= " + ShortestNumber(request.to);
  return sql + " ORDER BY r.step, s.busIndex, r.receivedUtime";
}

}  // namespace

uint64_t ExportReadingsCsv(DbConnection* db, const ReadingsRequest& request, std::ostream& out) {
  if (request.from > request.to)
    throw Error("--from " + ShortestNumber(request.from) + " is after --to " +
                ShortestNumber(request.to));
  const uint32_t simulation = ResolveSimulation(db, request.simulation);
  if (!request.sensor.empty())
    RequirePartName(db, simulation, PartKind::kSensor, request.sensor);
  const bool wide = !request.sensor.empty();
  bool header_written = false;
  if (!wide) {
    out << "time_s,step,sensor,kind,layer,column,value\n";
    header_written = true;
  }
  std::unique_ptr<sql::ResultSet> rows =
      db->QueryStreaming(ReadingsSql(simulation, request), "export readings");
  uint64_t count = 0;
  try {
    while (rows->next()) {
      LoggedReading r;
      r.time = static_cast<double>(rows->getDouble(1));
      r.step = rows->getInt64(2);
      r.sensor = rows->getString(3);
      r.layout = StoredSensor(rows->getString(4), rows->getString(5));
      r.values = SplitValues(rows->getString(6));
      r.text = rows->getString(7);
      count += wide ? WriteWide(r, &header_written, out) : WriteLong(r, out);
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the sensor readings");
  }
  if (!header_written) {
    // No readings: the header of the sensor's kind all the same.
    std::unique_ptr<sql::ResultSet> s = db->Query(
        "SELECT type, params FROM Sensor WHERE simulationID = " + std::to_string(simulation) +
            " AND name = " + Quoted(request.sensor),
        "SELECT type, params FROM Sensor");
    try {
      if (s->next()) out << WideHeader(StoredSensor(s->getString(1), s->getString(2))) << "\n";
    } catch (const sql::SQLException&) {
      db->Rethrow("read the sensor");
    }
  }
  return count;
}

}  // namespace simpartner::logger
