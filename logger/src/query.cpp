#include "simpartner/logger/query.h"

#include <cppconn/exception.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "simpartner/edit_distance.h"
#include "simpartner/logger/sql_text.h"

namespace simpartner::logger {
namespace {

uint32_t ResolveSimulation(DbConnection* db, const std::string& which) {
  if (which == "last") {
    const int64_t id = db->QueryInt("SELECT MAX(simulationID) FROM Simulation",
                                    "SELECT MAX(simulationID) FROM Simulation", -1);
    if (id < 0) throw Error("the database '" + db->target().database + "' has no simulations yet");
    return static_cast<uint32_t>(id);
  }
  if (which == "running") {
    const int64_t id =
        db->QueryInt("SELECT MAX(simulationID) FROM Simulation WHERE endTime IS NULL",
                     "SELECT MAX(simulationID) FROM Simulation (open)", -1);
    if (id < 0)
      throw Error("no simulation is running (every simulation in database '" +
                  db->target().database + "' has ended; 'last' is the newest)");
    return static_cast<uint32_t>(id);
  }
  char* end = nullptr;
  const unsigned long id = std::strtoul(which.c_str(), &end, 10);
  if (which.empty() || *end != '\0' || id == 0 || id > 0xFFFFFFFFul)
    throw Error("simulation '" + which +
                "' is not a simulationID (a positive number), 'last' or 'running'");
  if (db->QueryInt("SELECT COUNT(*) FROM Simulation WHERE simulationID = " + std::to_string(id),
                   "SELECT FROM Simulation", 0) == 0)
    throw Error("no simulation " + which + " in database '" + db->target().database +
                "' (simpartner-query list shows them)");
  return static_cast<uint32_t>(id);
}

// The names of a simulation's bodies or joints, in bus order.
std::vector<std::string> NamesOf(DbConnection* db, uint32_t simulation, bool joints) {
  const std::string table = joints ? "`Joint`" : "Body";
  std::unique_ptr<sql::ResultSet> rows =
      db->Query("SELECT name FROM " + table + " WHERE simulationID = " +
                    std::to_string(simulation) + " ORDER BY busIndex",
                "SELECT name FROM " + table);
  std::vector<std::string> names;
  try {
    while (rows->next()) names.push_back(rows->getString(1));
  } catch (const sql::SQLException&) {
    db->Rethrow("read the names of " + table);
  }
  return names;
}

// Throws Error when `name` is not a body (joint) of the simulation, with
// the nearest names.
void CheckName(DbConnection* db, uint32_t simulation, bool joint, const std::string& name) {
  const std::vector<std::string> names = NamesOf(db, simulation, joint);
  for (const std::string& n : names)
    if (n == name) return;
  std::string message = "simulation " + std::to_string(simulation) + " has no " +
                        (joint ? "joint" : "body") + " named '" + name + "'";
  size_t best = std::string::npos;
  std::string nearest;
  for (const std::string& n : names) {
    const size_t d = EditDistance(n, name);
    if (d < best) {
      best = d;
      nearest = n;
    }
  }
  if (!nearest.empty() && best <= std::max<size_t>(2, name.size() / 3))
    message += " (did you mean '" + nearest + "'?)";
  else if (!names.empty()) {
    message += "; its " + std::string(joint ? "joints" : "bodies") + ":";
    for (size_t i = 0; i < names.size() && i < 40; ++i) message += (i ? ", " : " ") + names[i];
  }
  throw Error(message);
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += "\"\"";
    else out += c;
  }
  return out + "\"";
}

}  // namespace

void ListSimulations(DbConnection* db, std::ostream& out) {
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      "SELECT s.simulationID, s.busSimulationID, s.host, s.worldName, s.startTime, s.endTime, "
      "(SELECT COUNT(*) FROM SimulationRow r WHERE r.simulationID = s.simulationID), "
      "(SELECT MAX(step) FROM SimulationRow r WHERE r.simulationID = s.simulationID), "
      "(SELECT COALESCE(SUM(missing), 0) FROM LogGap g WHERE g.simulationID = s.simulationID), "
      "COALESCE(s.endReason, 'open') "
      "FROM Simulation s ORDER BY s.simulationID",
      "list simulations");
  char line[512];
  std::snprintf(line, sizeof line, "%-6s %-18s %-16s %-20s %-26s %-26s %10s %10s %8s  %s\n", "id",
                "bus id", "host", "world", "start (UTC)", "end (UTC)", "steps", "last step",
                "missing", "state");
  out << line;
  try {
    while (rows->next()) {
      std::snprintf(line, sizeof line, "%-6u %-18lld %-16s %-20s %-26s %-26s %10lld %10s %8lld  %s\n",
                    rows->getUInt(1), static_cast<long long>(rows->getInt64(2)),
                    std::string(rows->getString(3)).c_str(), std::string(rows->getString(4)).c_str(),
                    std::string(rows->getString(5)).c_str(),
                    rows->isNull(6) ? "-" : std::string(rows->getString(6)).c_str(),
                    static_cast<long long>(rows->getInt64(7)),
                    rows->isNull(8) ? "-" : std::string(rows->getString(8)).c_str(),
                    static_cast<long long>(rows->getInt64(9)), std::string(rows->getString(10)).c_str());
      out << line;
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the list of simulations");
  }
}

namespace {

// Columns of JointPose after the name: anchor x, y, z, then angle, angle2,
// angle3 (indices 3..5).
constexpr size_t kJointAngleColumn = 3;
constexpr double kPi = 3.14159265358979323846;

std::string Number(double value) {
  std::string text;
  AppendDouble(&text, value);
  return text;
}

// How many of a joint type's axes are rotations (the rest are metres or none).
int RotationalAxes(const std::string& type) {
  if (type == "HINGE") return 1;
  if (type == "UNIVERSAL" || type == "HINGE2") return 2;
  return 0;
}

// Per body or joint: the previous raw angles and the whole turns added.
struct UnwrapState {
  double previous[3] = {0, 0, 0};
  double offset[3] = {0, 0, 0};
  bool seen = false;
};

// Velocity of the row `index` of `at` from the same body in `before` and
// `after` (x, y, z are values 0..2); NaN if it is missing in either.
void AppendVelocity(const ExportStep& before, const ExportStep& after, ExportRow* row) {
  const ExportRow* a = nullptr;
  const ExportRow* b = nullptr;
  for (const ExportRow& r : before.rows)
    if (r.name == row->name) a = &r;
  for (const ExportRow& r : after.rows)
    if (r.name == row->name) b = &r;
  const double dt = after.time - before.time;
  for (int k = 0; k < 3; ++k)
    row->values.push_back(a != nullptr && b != nullptr && dt > 0
                              ? (b->values[static_cast<size_t>(k)] - a->values[static_cast<size_t>(k)]) / dt
                              : std::numeric_limits<double>::quiet_NaN());
}

// Wheel1, wheel_left ...: what wheel-forces draws by default.
bool IsWheelName(const std::string& name) {
  return name.size() >= 5 && EditDistance(name.substr(0, 5), "wheel") == 0;
}

}  // namespace

std::vector<std::string> ExportColumns(const ExportRequest& request) {
  switch (request.kind) {
    case ExportKind::kPoses: {
      std::vector<std::string> c = {"x_m", "y_m", "z_m", "axis_x", "axis_y", "axis_z", "angle_rad"};
      if (request.velocities) c.insert(c.end(), {"vx_m_s", "vy_m_s", "vz_m_s"});
      return c;
    }
    case ExportKind::kForces:
      return {"Fx_N", "Fy_N", "Fz_N", "Tx_Nm", "Ty_Nm", "Tz_Nm"};
    case ExportKind::kJoints:
      return {"anchor_x_m", "anchor_y_m", "anchor_z_m", "angle", "angle2", "angle3", "rate",
              "rate2", "rate3", "F1x_N", "F1y_N", "F1z_N", "T1x_Nm", "T1y_Nm", "T1z_Nm"};
  }
  return {};
}

uint32_t ReadExport(DbConnection* db, const ExportRequest& request,
                    const std::function<void(const ExportStep&)>& sink) {
  if (request.every < 1)
    throw Error("--every " + std::to_string(request.every) + ": must be 1 or more (every Nth step)");
  if (request.from > request.to)
    throw Error("--from " + Number(request.from) + " is after --to " + Number(request.to));
  if (request.velocities && request.kind != ExportKind::kPoses)
    throw Error("--velocities is for poses (joints carry their rates in rate, rate2, rate3)");
  if (request.unwrap && request.kind != ExportKind::kJoints)
    throw Error("--unwrap is for joints (their angle, angle2, angle3)");
  const uint32_t simulation = ResolveSimulation(db, request.simulation);
  const bool joints = request.kind == ExportKind::kJoints;
  if (!request.name.empty()) CheckName(db, simulation, joints, request.name);
  const std::string sim = std::to_string(simulation);

  // The time between logged steps, to read one more on each side of the
  // range for the central differences.
  double logged_dt = 0;
  {
    std::unique_ptr<sql::ResultSet> r = db->Query(
        "SELECT stepSize * stateEvery * logInterval FROM Simulation WHERE simulationID = " + sim,
        "SELECT stepSize FROM Simulation");
    try {
      if (r->next()) logged_dt = static_cast<double>(r->getDouble(1));
    } catch (const sql::SQLException&) {
      db->Rethrow("read the step size");
    }
  }
  std::map<std::string, int> rotational_axes;
  if (request.unwrap) {
    std::unique_ptr<sql::ResultSet> r = db->Query(
        "SELECT name, type FROM `Joint` WHERE simulationID = " + sim, "SELECT type FROM `Joint`");
    try {
      while (r->next()) rotational_axes[r->getString(1)] = RotationalAxes(r->getString(2));
    } catch (const sql::SQLException&) {
      db->Rethrow("read the joint types");
    }
  }
  // Joints logged with the sim's continuous angle (schema 5 on, a sim that
  // publishes it): --unwrap takes it as stored, which is right however far
  // an axis turned between logged steps and needs no steps before --from.
  bool stored_continuous = false;
  if (request.unwrap) {
    stored_continuous =
        db->QueryInt("SELECT COUNT(*) FROM information_schema.COLUMNS WHERE TABLE_SCHEMA = "
                     "DATABASE() AND LOWER(TABLE_NAME) = 'jointpose' AND COLUMN_NAME = "
                     "'continuousAngle'",
                     "look for JointPose.continuousAngle", 0) > 0 &&
        db->QueryInt("SELECT p.continuousAngle IS NOT NULL FROM SimulationRow r JOIN JointPose p "
                     "ON p.simulationRowID = r.simulationRowID WHERE r.simulationID = " + sim +
                     " ORDER BY r.step LIMIT 1",
                     "SELECT continuousAngle FROM JointPose", 0) == 1;
  }
  // Unwrapping here needs every angle from the start; velocities one step more.
  std::string range;
  const double margin = request.velocities ? 1.5 * logged_dt : 0;
  if (std::isfinite(request.from) && (!request.unwrap || stored_continuous))
    range += " AND r.simulationTime >= " + Number(request.from - margin);
  if (std::isfinite(request.to)) range += " AND r.simulationTime <= " + Number(request.to + margin);
  const std::string name_filter =
      request.name.empty() ? "" : std::string(joints ? " AND j.name = " : " AND b.name = ") + Quoted(request.name);
  std::string sql;
  switch (request.kind) {
    case ExportKind::kPoses:
      sql = "SELECT r.simulationTime, r.step, b.name, p.x, p.y, p.z, p.axisX, p.axisY, p.axisZ, "
            "p.angle FROM SimulationRow r JOIN Pose p ON p.simulationRowID = r.simulationRowID "
            "JOIN Body b ON b.bodyID = p.bodyID WHERE r.simulationID = " + sim + range + name_filter +
            " ORDER BY r.step, b.busIndex";
      break;
    case ExportKind::kForces:
      sql = "SELECT r.simulationTime, r.step, b.name, f.F_x, f.F_y, f.F_z, f.T_x, f.T_y, f.T_z "
            "FROM SimulationRow r JOIN ForceAndTorque f ON f.simulationRowID = r.simulationRowID "
            "JOIN Body b ON b.bodyID = f.bodyID WHERE r.simulationID = " + sim + range + name_filter +
            " ORDER BY r.step, b.busIndex";
      break;
    case ExportKind::kJoints:
      sql = "SELECT r.simulationTime, r.step, j.name, p.anchorx, p.anchory, p.anchorz, p.angle, "
            "p.angle2, p.angle3, p.rate, p.rate2, p.rate3, p.F_x, p.F_y, p.F_z, p.T_x, p.T_y, p.T_z" +
            std::string(stored_continuous
                            ? ", p.continuousAngle, p.continuousAngle2, p.continuousAngle3 "
                            : " ") +
            "FROM SimulationRow r JOIN JointPose p ON p.simulationRowID = r.simulationRowID "
            "JOIN `Joint` j ON j.jointID = p.jointID WHERE r.simulationID = " + sim + range + name_filter +
            " ORDER BY r.step, j.busIndex";
      break;
  }
  constexpr size_t kJointNumbers = 15;
  const size_t numbers = request.kind == ExportKind::kPoses    ? 7
                         : request.kind == ExportKind::kForces ? 6
                         : stored_continuous                   ? kJointNumbers + 3
                                                               : kJointNumbers;

  int64_t in_range = 0;  // steps of the range seen, for --every
  auto emit = [&](const ExportStep& step) {
    if (step.time < request.from || step.time > request.to) return;
    if (in_range++ % request.every == 0) sink(step);
  };
  std::map<std::string, UnwrapState> unwrap;
  std::deque<ExportStep> window;  // velocities: the steps before and after
  bool first_emitted = false;
  auto take = [&](ExportStep step) {
    if (request.unwrap) {
      for (ExportRow& row : step.rows) {
        if (row.values.size() > kJointNumbers) {
          // The stored continuous angle (NaN where a row has none).
          const bool stored = !std::isnan(row.values[kJointNumbers]);
          if (stored)
            std::copy(row.values.begin() + kJointNumbers, row.values.begin() + kJointNumbers + 3,
                      row.values.begin() + kJointAngleColumn);
          row.values.resize(kJointNumbers);
          if (stored) continue;
        }
        const int axes = rotational_axes[row.name];
        UnwrapState& u = unwrap[row.name];
        for (int k = 0; k < axes; ++k) {
          double& angle = row.values[kJointAngleColumn + static_cast<size_t>(k)];
          if (u.seen) {
            const double jump = angle - u.previous[k];
            if (jump > kPi) u.offset[k] -= 2 * kPi;
            else if (jump < -kPi) u.offset[k] += 2 * kPi;
          }
          u.previous[k] = angle;
          angle += u.offset[k];
        }
        u.seen = true;
      }
    }
    if (!request.velocities) return emit(step);
    window.push_back(std::move(step));
    if (window.size() == 2 && !first_emitted) {
      ExportStep first = window[0];
      for (ExportRow& row : first.rows) AppendVelocity(window[0], window[1], &row);
      emit(first);
      first_emitted = true;
    } else if (window.size() == 3) {
      ExportStep middle = window[1];
      for (ExportRow& row : middle.rows) AppendVelocity(window[0], window[2], &row);
      emit(middle);
      window.pop_front();
    }
  };

  std::unique_ptr<sql::ResultSet> rows = db->QueryStreaming(sql, "export");
  ExportStep current;
  bool have_current = false;
  try {
    while (rows->next()) {
      const int64_t step = rows->getInt64(2);
      if (!have_current || step != current.step) {
        if (have_current) take(std::move(current));
        current = ExportStep();
        current.time = static_cast<double>(rows->getDouble(1));
        current.step = step;
        have_current = true;
      }
      ExportRow row;
      row.name = rows->getString(3);
      row.values.reserve(numbers + 3);
      for (size_t k = 0; k < numbers; ++k) {
        const auto column = static_cast<uint32_t>(4 + k);
        row.values.push_back(rows->isNull(column) ? std::numeric_limits<double>::quiet_NaN()
                                                  : static_cast<double>(rows->getDouble(column)));
      }
      current.rows.push_back(std::move(row));
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the export rows");
  }
  if (have_current) take(std::move(current));
  if (request.velocities) {
    if (window.size() == 1 && !first_emitted) {
      ExportStep only = window[0];
      for (ExportRow& row : only.rows) AppendVelocity(window[0], window[0], &row);
      emit(only);
    } else if (window.size() == 2) {
      ExportStep last = window[1];
      for (ExportRow& row : last.rows) AppendVelocity(window[0], window[1], &row);
      emit(last);
    }
  }
  return simulation;
}

uint64_t ExportCsv(DbConnection* db, const ExportRequest& request, std::ostream& out) {
  const std::vector<std::string> columns = ExportColumns(request);
  std::string header = "time_s,step,";
  header += request.kind == ExportKind::kJoints ? "joint" : "body";
  for (const std::string& c : columns) header += "," + c;
  uint64_t count = 0;
  std::string line;
  bool header_written = false;
  auto write_header = [&] {
    if (header_written) return;
    if (request.velocities)
      out << "# vx_m_s, vy_m_s, vz_m_s: central differences of the logged x, y, z (the logger "
             "stores no body velocities); one-sided at the first and last logged step\n";
    if (request.unwrap)
      out << "# angle, angle2, angle3 of rotational axes unwrapped: continuous, no jump at +-pi "
             "(as the sim counted them every step; from the first logged step for simulations "
             "logged before it did)\n";
    out << header << "\n";
    header_written = true;
  };
  ReadExport(db, request, [&](const ExportStep& step) {
    write_header();
    for (const ExportRow& row : step.rows) {
      line.clear();
      AppendDouble(&line, step.time);
      line.push_back(',');
      AppendInt(&line, step.step);
      line.push_back(',');
      line += CsvField(row.name);
      for (double v : row.values) {
        line.push_back(',');
        AppendDouble(&line, v);
      }
      line.push_back('\n');
      out << line;
      ++count;
    }
  });
  write_header();
  return count;
}

PlotKind ParsePlotKind(const std::string& word) {
  static const std::vector<std::pair<std::string, PlotKind>> kKinds = {
      {"position", PlotKind::kPosition}, {"velocity", PlotKind::kVelocity},
      {"angle", PlotKind::kAngle},       {"rate", PlotKind::kRate},
      {"force", PlotKind::kForce},       {"wheel-forces", PlotKind::kWheelForces},
      {"track", PlotKind::kTrack}};
  std::string list, nearest;
  size_t best = std::string::npos;
  for (const auto& [name, kind] : kKinds) {
    if (name == word) return kind;
    list += (list.empty() ? "" : ", ") + name;
    const size_t d = EditDistance(name, word);
    if (d < best) {
      best = d;
      nearest = name;
    }
  }
  throw Error("plot: unknown quantity '" + word + "'" +
              (best <= 3 ? " (did you mean '" + nearest + "'?)" : "") + "; one of " + list);
}

Plot MakePlot(DbConnection* db, const PlotRequest& request) {
  ExportRequest e;
  e.simulation = request.simulation;
  e.name = request.name;
  e.from = request.from;
  e.to = request.to;
  const bool needs_joint = request.kind == PlotKind::kAngle || request.kind == PlotKind::kRate ||
                           request.kind == PlotKind::kForce;
  e.kind = needs_joint                                ? ExportKind::kJoints
           : request.kind == PlotKind::kWheelForces ? ExportKind::kForces
                                                      : ExportKind::kPoses;
  e.velocities = request.kind == PlotKind::kVelocity;
  e.unwrap = request.kind == PlotKind::kAngle;
  const uint32_t simulation = ResolveSimulation(db, request.simulation);
  e.simulation = std::to_string(simulation);
  const std::string sim = e.simulation;
  if (e.name.empty() && request.kind == PlotKind::kTrack) {
    // The track of the first robot's first body (its chassis) by default.
    std::unique_ptr<sql::ResultSet> r =
        db->Query("SELECT name FROM Body WHERE simulationID = " + sim +
                      " ORDER BY robotID IS NULL, busIndex LIMIT 1",
                  "SELECT name FROM Body");
    try {
      if (r->next()) e.name = r->getString(1);
    } catch (const sql::SQLException&) {
      db->Rethrow("read the first body");
    }
    if (e.name.empty()) throw Error("simulation " + sim + " has no bodies to draw a track of");
  }
  if (e.name.empty() && request.kind != PlotKind::kWheelForces)
    throw Error(std::string("plot needs ") + (needs_joint ? "--joint NAME" : "--body NAME") +
                " (simpartner-query names SIM lists them)");

  Plot plot;
  std::string world;
  double gravity[3] = {0, 0, 0};
  {
    std::unique_ptr<sql::ResultSet> r = db->Query(
        "SELECT worldName, gravityX, gravityY, gravityZ FROM Simulation WHERE simulationID = " + sim,
        "SELECT worldName FROM Simulation");
    try {
      if (r->next()) {
        world = r->getString(1);
        for (uint32_t k = 0; k < 3; ++k) gravity[k] = static_cast<double>(r->getDouble(2 + k));
      }
    } catch (const sql::SQLException&) {
      db->Rethrow("read the simulation");
    }
  }
  const std::string where = "simulation " + sim + " (" + world + ")";
  plot.xlabel = "simulation time [s]";
  std::map<std::string, size_t> series_of;  // name + column -> index in plot.series
  auto add = [&](const std::string& title, double x, double y) {
    auto it = series_of.find(title);
    if (it == series_of.end()) {
      it = series_of.emplace(title, plot.series.size()).first;
      plot.series.push_back(Series{title, {}, {}, "lines"});
    }
    plot.series[it->second].x.push_back(x);
    plot.series[it->second].y.push_back(y);
  };
  const double g = std::sqrt(gravity[0] * gravity[0] + gravity[1] * gravity[1] + gravity[2] * gravity[2]);
  if (request.kind == PlotKind::kWheelForces && request.name.empty()) {
    const std::vector<std::string> bodies = NamesOf(db, simulation, false);
    if (std::none_of(bodies.begin(), bodies.end(), IsWheelName))
      throw Error(where + " has no body named Wheel*; name one with --body");
  }
  ReadExport(db, e, [&](const ExportStep& step) {
    for (const ExportRow& row : step.rows) {
      const std::vector<double>& v = row.values;
      switch (request.kind) {
        case PlotKind::kPosition:
          add("x", step.time, v[0]);
          add("y", step.time, v[1]);
          add("z", step.time, v[2]);
          break;
        case PlotKind::kVelocity:
          add("vx", step.time, v[7]);
          add("vy", step.time, v[8]);
          add("vz", step.time, v[9]);
          add("speed", step.time, std::sqrt(v[7] * v[7] + v[8] * v[8] + v[9] * v[9]));
          break;
        case PlotKind::kAngle:
          add("angle (continuous)", step.time, v[3]);
          break;
        case PlotKind::kRate:
          add("rate", step.time, v[6]);
          break;
        case PlotKind::kForce:
          add("F1x", step.time, v[9]);
          add("F1y", step.time, v[10]);
          add("F1z", step.time, v[11]);
          add("|F1|", step.time, std::sqrt(v[9] * v[9] + v[10] * v[10] + v[11] * v[11]));
          break;
        case PlotKind::kWheelForces: {
          if (request.name.empty() && !IsWheelName(row.name)) break;
          // The load: the contact force against gravity (|F| without gravity).
          const double up = g > 0 ? -(v[0] * gravity[0] + v[1] * gravity[1] + v[2] * gravity[2]) / g
                                  : std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
          add(row.name, step.time, up);
          break;
        }
        case PlotKind::kTrack:
          add(row.name, v[0], v[2]);
          break;
      }
    }
  });
  switch (request.kind) {
    case PlotKind::kPosition:
      plot.title = where + ": position of " + e.name;
      plot.ylabel = "position [m]";
      break;
    case PlotKind::kVelocity:
      plot.title = where + ": velocity of " + e.name + " (central differences of the logged positions)";
      plot.ylabel = "velocity [m/s]";
      break;
    case PlotKind::kAngle:
      plot.title = where + ": angle of joint " + e.name;
      plot.ylabel = "angle [rad] (slider: [m])";
      break;
    case PlotKind::kRate:
      plot.title = where + ": rate of joint " + e.name;
      plot.ylabel = "rate [rad/s] (slider: [m/s])";
      break;
    case PlotKind::kForce:
      plot.title = where + ": constraint force of joint " + e.name + " on its body1";
      plot.ylabel = "force [N]";
      break;
    case PlotKind::kWheelForces:
      plot.title = where + ": wheel contact forces against gravity" +
                   (request.name.empty() ? "" : " (" + request.name + ")");
      plot.ylabel = g > 0 ? "contact force along up [N]" : "|contact force| [N]";
      break;
    case PlotKind::kTrack:
      plot.title = where + ": track of " + e.name + " seen from above";
      plot.xlabel = "x [m]";
      plot.ylabel = "z [m]";
      plot.equal_axes = true;
      break;
  }
  if (plot.series.empty())
    throw Error(where + " has no logged steps" +
                (std::isfinite(request.from) || std::isfinite(request.to) ? " in the time range" : "") +
                " to plot");
  return plot;
}

namespace {

// The tables with a simulationID column, children first.
const char* const kTablesBySimulation[] = {"LogGap", "SensorReading", "Command", "CommandReply",
                                           "Sensor", "Actuator", "`Joint`", "Body"};

DeleteSummary DeleteIds(DbConnection* db, const std::vector<uint32_t>& ids) {
  DeleteSummary summary;
  if (ids.empty()) return summary;
  std::string list;
  for (uint32_t id : ids) list += (list.empty() ? "" : ", ") + std::to_string(id);
  try {
    db->Begin();
    summary.steps = static_cast<uint64_t>(db->QueryInt(
        "SELECT COUNT(*) FROM SimulationRow WHERE simulationID IN (" + list + ")", "count steps", 0));
    for (const char* table : {"Pose", "ForceAndTorque", "JointPose"})
      db->Execute(std::string("DELETE t FROM ") + table +
                      " t JOIN SimulationRow r ON r.simulationRowID = t.simulationRowID "
                      "WHERE r.simulationID IN (" + list + ")",
                  std::string("DELETE FROM ") + table);
    db->Execute("DELETE FROM SimulationRow WHERE simulationID IN (" + list + ")",
                "DELETE FROM SimulationRow");
    db->Execute("DELETE c FROM RobotComponent c JOIN Robot r ON r.robotID = c.robotID "
                "WHERE r.simulationID IN (" + list + ")",
                "DELETE FROM RobotComponent");
    for (const char* table : kTablesBySimulation)
      db->Execute(std::string("DELETE FROM ") + table + " WHERE simulationID IN (" + list + ")",
                  std::string("DELETE FROM ") + table);
    db->Execute("DELETE FROM Robot WHERE simulationID IN (" + list + ")", "DELETE FROM Robot");
    db->Execute("DELETE FROM Simulation WHERE simulationID IN (" + list + ")", "DELETE FROM Simulation");
    db->Commit();
  } catch (const DbError& e) {
    db->Rollback();
    // 1142: command denied to user (no DELETE privilege).
    if (e.code() == 1142)
      throw Error("deleting needs an administrator: " + e.server() + " refuses DELETE to this user (" +
                  e.cause() + "); the logger's and the reader's users have no DELETE. Use "
                  "--db-options with the administrator's option file (the private server's is "
                  "admin.cnf beside its reader.cnf, the default of delete and prune). Nothing was "
                  "deleted");
    throw;
  }
  summary.simulations = ids;
  return summary;
}

}  // namespace

DeleteSummary DeleteSimulation(DbConnection* db, const std::string& simulation, bool even_if_open) {
  if (simulation == "last" || simulation == "running")
    throw Error("delete takes a simulationID, not '" + simulation + "' (simpartner-query list shows them)");
  const uint32_t id = ResolveSimulation(db, simulation);
  if (!even_if_open &&
      db->QueryInt("SELECT COUNT(*) FROM Simulation WHERE endTime IS NULL AND simulationID = " +
                       std::to_string(id),
                   "SELECT FROM Simulation", 0) > 0)
    throw Error("simulation " + std::to_string(id) +
                " is still open (being logged, or its logger stopped before it ended); stop it "
                "first, or give --force");
  return DeleteIds(db, {id});
}

DeleteSummary PruneSimulations(DbConnection* db, int64_t keep) {
  if (keep < 0) throw Error("prune --keep " + std::to_string(keep) + ": must be 0 or more");
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      "SELECT simulationID, endTime IS NULL FROM Simulation ORDER BY simulationID DESC",
      "SELECT simulationID FROM Simulation");
  std::vector<uint32_t> doomed;
  int64_t kept = 0;
  try {
    while (rows->next()) {
      const uint32_t id = rows->getUInt(1);
      const bool open = rows->getInt(2) != 0;
      if (kept < keep || open) {
        ++kept;  // the newest `keep`, and every open one (still being logged)
        continue;
      }
      doomed.push_back(id);
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the list of simulations");
  }
  std::sort(doomed.begin(), doomed.end());
  return DeleteIds(db, doomed);
}

const std::vector<std::string>& PerStepTables() {
  static const std::vector<std::string> tables = {"SimulationRow", "Pose", "ForceAndTorque",
                                                  "JointPose"};
  return tables;
}

bool PageCompressedOption(const std::string& create_options) {
  // MariaDB 10.11 writes `page_compressed`='1' (quoted) in CREATE_OPTIONS;
  // the value may also come unquoted or as ON.
  const std::string key = "page_compressed`=";
  const size_t at = create_options.find(key);
  if (at == std::string::npos) return false;
  std::string value = create_options.substr(at + key.size());
  value = value.substr(0, value.find(' '));
  value.erase(std::remove(value.begin(), value.end(), '\''), value.end());
  std::transform(value.begin(), value.end(), value.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return value == "1" || value == "on" || value == "yes";
}

std::vector<TableStorage> ReadTableStorage(DbConnection* db) {
  std::string list;
  for (const std::string& t : PerStepTables()) list += (list.empty() ? "" : ", ") + t;
  // FOR EXPORT writes the tables' dirty pages, so the files hold what they will.
  db->Execute("FLUSH TABLES " + list + " FOR EXPORT", "FLUSH TABLES FOR EXPORT");
  db->Execute("UNLOCK TABLES", "UNLOCK TABLES");
  std::vector<TableStorage> out;
  for (const std::string& t : PerStepTables()) {
    db->Query("ANALYZE TABLE " + t, "ANALYZE TABLE " + t);
    std::unique_ptr<sql::ResultSet> r = db->Query(
        "SELECT t.TABLE_ROWS, t.DATA_LENGTH + t.INDEX_LENGTH, s.ALLOCATED_SIZE, "
        "LOWER(t.CREATE_OPTIONS) FROM information_schema.TABLES t "
        "LEFT JOIN information_schema.INNODB_SYS_TABLESPACES s "
        "ON s.NAME = CONCAT(t.TABLE_SCHEMA, '/', t.TABLE_NAME) "
        "WHERE t.TABLE_SCHEMA = DATABASE() AND LOWER(t.TABLE_NAME) = LOWER(" + Quoted(t) + ")",
        "the size of " + t);
    try {
      if (!r->next()) throw Error("database has no table " + t + " (has the logger run on it?)");
      TableStorage ts;
      ts.table = t;
      ts.rows = r->getUInt64(1);
      ts.logical_bytes = r->getUInt64(2);
      ts.disk_bytes = r->isNull(3) ? 0 : r->getUInt64(3);
      ts.compressed = PageCompressedOption(r->getString(4));
      out.push_back(ts);
    } catch (const sql::SQLException&) {
      db->Rethrow("read the size of " + t);
    }
  }
  return out;
}

void SetPageCompression(DbConnection* db, bool on) {
  for (const std::string& t : PerStepTables())
    db->Execute("ALTER TABLE " + t + " PAGE_COMPRESSED=" + (on ? "1" : "0"),
                "ALTER TABLE " + t + " PAGE_COMPRESSED (needs the administrator: the private "
                "server's admin.cnf, or --db-options)");
}

}  // namespace simpartner::logger
