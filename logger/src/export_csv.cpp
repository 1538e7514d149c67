// The CSV of an export: comment lines saying how derived columns were
// obtained, a header line, then one line per body or joint and step.
#include <ostream>

#include "simpartner/csv_field.h"
#include "simpartner/logger/export.h"
#include "simpartner/logger/sql_text.h"

namespace simpartner::logger {

namespace {

void WriteHeader(const ExportRequest& request, std::ostream& out) {
  if (request.velocities)
    out << "# vx_m_s, vy_m_s, vz_m_s: central differences of the logged x, y, z (the logger "
           "stores no body velocities); one-sided at the first and last logged step\n";
  if (request.unwrap)
    out << "# angle, angle2, angle3 of rotational axes unwrapped: continuous, no jump at +-pi "
           "(as the sim counted them every step; from the first logged step for simulations "
           "logged before it did)\n";
  std::string header = "time_s,step,";
  header += request.kind == ExportKind::kJoints ? "joint" : "body";
  for (const std::string& c : ExportColumns(request)) header += "," + c;
  out << header << "\n";
}

void AppendLine(const ExportStep& step, const ExportRow& row, std::string* line) {
  AppendDouble(line, step.time);
  line->push_back(',');
  AppendInt(line, step.step);
  line->push_back(',');
  *line += CsvField(row.name);
  for (double v : row.values) {
    line->push_back(',');
    AppendDouble(line, v);
  }
  line->push_back('\n');
}

}  // namespace

uint64_t ExportCsv(DbConnection* db, const ExportRequest& request, std::ostream& out) {
  uint64_t count = 0;
  std::string line;
  bool header_written = false;
  // The header after the request is known good (an unknown body writes nothing).
  auto write_header = [&] {
    if (!header_written) WriteHeader(request, out);
    header_written = true;
  };
  ReadExport(db, request, [&](const ExportStep& step) {
    write_header();
    for (const ExportRow& row : step.rows) {
      line.clear();
      AppendLine(step, row, &line);
      out << line;
      ++count;
    }
  });
  write_header();
  return count;
}

}  // namespace simpartner::logger
