#include "simpartner/logger/writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <set>
#include <unordered_map>

#include <cppconn/exception.h>

#include "simpartner/bus_decode.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_shape.h"
#include "simpartner/command_t.hpp"
#include "simpartner/logger/axis_angle.h"
#include "simpartner/logger/receiver.h"
#include "simpartner/logger/schema.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/state_t.hpp"

namespace simpartner::logger {
namespace {

// The last step of a simulation in the database, -1 if none.
int64_t LastLoggedStep(DbConnection* db, uint32_t simulation) {
  return db->QueryInt("SELECT MAX(step) FROM SimulationRow WHERE simulationID = " +
                          std::to_string(simulation),
                      "SELECT MAX(step) FROM SimulationRow", -1);
}

constexpr size_t kInsertStatementBytes = 1 << 20;
constexpr size_t kLoadDataFileBytes = 16 << 20;
constexpr int kDuplicateKey = 1062;  // ER_DUP_ENTRY
// Below this many steps a batch goes as INSERTs: LOAD DATA's fixed cost per
// statement (a file per table) outweighs its cheaper rows.
constexpr size_t kLoadDataMinSteps = 25;

// The server or the client library will not do LOAD DATA LOCAL.
bool IsLoadDataRefused(int code) {
  return code == 1148 /* ER_NOT_ALLOWED_COMMAND */ || code == 4166 /* capability disabled */ ||
         code == 2068 /* CR_LOAD_DATA_LOCAL_INFILE_REJECTED */ || code == 3948;
}

int64_t NowMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Decodes a record's payload through the shared total decoder (the spool
// on disk is no more trusted than the bus). A record that does not decode
// is reported and skipped: retrying it could never succeed.
template <class Message>
bool DecodeRecord(const Record& record, Message* message, const DbWriter::Notice& notice) {
  const std::optional<DecodeFailure> failure =
      DecodeLcm(record.payload.data(), record.payload.size(), message);
  if (!failure) return true;
  notice(std::string("a ") + RecordKindName(record.kind) + " record of bus simulation " +
         std::to_string(record.simulation_id) + " does not decode; not written: " +
         DescribeRefusal("spool", Message::getTypeName(), record.payload.size(), *failure));
  return false;
}

// Text for a VARCHAR column from the logger's own messages (which may hold
// a path): valid UTF-8 of at most max_bytes bytes, other bytes as '?'.
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

// The LOAD DATA scratch file could not be written (the spool disk full):
// the batch is rolled back and goes again as INSERTs.
class ScratchFileError : public Error {
 public:
  using Error::Error;
};

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

const char* SensorName(int8_t kind) {
  switch (kind) {
    case 0: return "ECHO";
    case 1: return "POSITION";
    case 2: return "SCANNER";
    case 3: return "VELOCITY";
    case 4: return "FORCE_TORQUE";
  }
  return "UNKNOWN";
}

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
  return "FROM_UNIXTIME(" + std::to_string(micros / 1000000) + "." +
         [&] {
           char frac[8];
           std::snprintf(frac, sizeof frac, "%06lld", static_cast<long long>(micros % 1000000));
           return std::string(frac);
         }() +
         ")";
}

// Index -> database id, or NULL for -1 (the static world, no robot).
void AppendId(std::string* out, const std::vector<int64_t>& ids, int64_t index) {
  if (index < 0 || index >= static_cast<int64_t>(ids.size())) out->append("NULL");
  else AppendInt(out, ids[static_cast<size_t>(index)]);
}

}  // namespace

const char* InsertMethodName(InsertMethod method) {
  switch (method) {
    case InsertMethod::kMultiRowInsert: return "multi-row INSERT";
    case InsertMethod::kLoadDataLocal: return "LOAD DATA LOCAL";
    case InsertMethod::kAuto: return "multi-row INSERT or LOAD DATA LOCAL by batch size";
  }
  return "?";
}

// Rows of one table, sent as multi-row INSERTs or LOAD DATA LOCAL files.
class DbWriter::RowSink {
 public:
  RowSink(DbConnection* db, InsertMethod method, const std::string& scratch_dir,
          std::string table, std::string columns, std::string on_duplicate = "")
      : db_(db),
        load_data_(method == InsertMethod::kLoadDataLocal),
        scratch_path_(scratch_dir + "/loaddata-" + table + ".tsv"),
        table_(std::move(table)),
        columns_(std::move(columns)),
        on_duplicate_(std::move(on_duplicate)) {
    buffer_.reserve(load_data_ ? kLoadDataFileBytes + 65536 : kInsertStatementBytes + 65536);
    Start();
  }

  void BeginRow() {
    if (load_data_) {
      first_field_ = true;
    } else {
      if (rows_in_buffer_ > 0) buffer_.push_back(',');
      buffer_.push_back('(');
      first_field_ = true;
    }
  }
  void Double(double v) {
    Separator();
    if (load_data_ && !std::isfinite(v)) buffer_.append("\\N");
    else AppendDouble(&buffer_, v);
  }
  void Int(int64_t v) {
    Separator();
    AppendInt(&buffer_, v);
  }
  void Id(const std::vector<int64_t>& ids, int64_t index) {
    Separator();
    if (load_data_ && (index < 0 || index >= static_cast<int64_t>(ids.size()))) buffer_.append("\\N");
    else AppendId(&buffer_, ids, index);
  }
  void Text(std::string_view text) {
    Separator();
    if (load_data_) AppendTsvField(&buffer_, text);
    else AppendQuoted(&buffer_, text);
  }
  // A literal SQL expression (multi-row INSERT only).
  void Expression(const std::string& sql) {
    Separator();
    buffer_.append(sql);
  }
  void EndRow() {
    buffer_.push_back(load_data_ ? '\n' : ')');
    ++rows_in_buffer_;
    ++rows_;
    if (buffer_.size() >= (load_data_ ? kLoadDataFileBytes : kInsertStatementBytes)) Flush();
  }
  void Finish() { Flush(); }
  uint64_t rows() const { return rows_; }

 private:
  void Start() {
    buffer_.clear();
    rows_in_buffer_ = 0;
    if (!load_data_) buffer_ = "INSERT INTO " + table_ + " (" + columns_ + ") VALUES ";
  }
  void Separator() {
    if (!first_field_) buffer_.push_back(load_data_ ? '\t' : ',');
    first_field_ = false;
  }
  void Flush() {
    if (rows_in_buffer_ == 0) return;
    const std::string what = (load_data_ ? "LOAD DATA LOCAL INTO " : "INSERT INTO ") + table_ +
                             " (" + std::to_string(rows_in_buffer_) + " rows)";
    if (load_data_) {
      // Numbers only (the per-step tables have no text): read as bytes.
      WriteFile(what);
      // The file goes as soon as the server has read it: nothing stays in
      // the spool directory, and its space is free for the spool.
      struct RemoveFile {
        const std::string& path;
        ~RemoveFile() { ::unlink(path.c_str()); }
      } remove{scratch_path_};
      db_->Execute("LOAD DATA LOCAL INFILE " + Quoted(scratch_path_) + " INTO TABLE " + table_ +
                       " CHARACTER SET binary FIELDS TERMINATED BY '\\t' LINES TERMINATED BY "
                       "'\\n' (" + columns_ + ")",
                   what);
    } else {
      if (!on_duplicate_.empty()) buffer_ += " ON DUPLICATE KEY UPDATE " + on_duplicate_;
      db_->Execute(buffer_, what);
    }
    Start();
  }
  void WriteFile(const std::string& what) {
    const int fd = ::open(scratch_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0)
      throw ScratchFileError(what + ": cannot write " + scratch_path_ + ": " + std::strerror(errno));
    size_t done = 0;
    while (done < buffer_.size()) {
      const ssize_t n = ::write(fd, buffer_.data() + done, buffer_.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const std::string cause = std::strerror(errno);
        ::close(fd);
        ::unlink(scratch_path_.c_str());
        throw ScratchFileError(what + ": cannot write " + scratch_path_ + ": " + cause);
      }
      done += static_cast<size_t>(n);
    }
    if (::close(fd) != 0) {
      const std::string cause = std::strerror(errno);
      ::unlink(scratch_path_.c_str());
      throw ScratchFileError(what + ": cannot write " + scratch_path_ + ": " + cause);
    }
  }

  DbConnection* db_;
  bool load_data_;
  std::string scratch_path_;
  std::string table_;
  std::string columns_;
  std::string on_duplicate_;
  std::string buffer_;
  bool first_field_ = true;
  size_t rows_in_buffer_ = 0;
  uint64_t rows_ = 0;
};

DbWriter::DbWriter(DbTarget target, WriterOptions options, Notice notice)
    : target_(std::move(target)), options_(std::move(options)), notice_(std::move(notice)) {}

DbWriter::~DbWriter() = default;

void DbWriter::Connect() {
  if (db_) return;
  std::unique_ptr<DbConnection> db =
      DbConnection::Open(target_, options_.method != InsertMethod::kMultiRowInsert);
  MigrateSchema(db.get(), notice_);
  // After a lost connection the database, not our memory, says how far each
  // simulation got: whatever the old connection sent last may or may not
  // have been committed. A step that went missing then shows as a gap.
  for (auto& [bus_id, sim] : simulations_) sim.last_step = LastLoggedStep(db.get(), sim.id);
  db_ = std::move(db);
}

void DbWriter::Disconnect() { db_.reset(); }

WriteResult DbWriter::Write(const std::vector<Record>& records) {
  WriteResult result;
  Connect();
  try {
    size_t i = 0;
    while (i < records.size()) {
      const Record& record = records[i];
      if (record.kind == RecordKind::kModel) {
        WriteModel(record, &result);
        ++i;
      } else if (record.kind == RecordKind::kSimulationEnded) {
        CloseSimulation(record);
        ++i;
      } else if (record.kind == RecordKind::kSimulationReopened) {
        ReopenSimulation(record);
        ++i;
      } else {
        std::vector<const Record*> run;
        while (i < records.size() && records[i].kind != RecordKind::kModel &&
               records[i].kind != RecordKind::kSimulationEnded &&
               records[i].kind != RecordKind::kSimulationReopened) {
          run.push_back(&records[i]);
          ++i;
        }
        WriteRunAtomically(run, &result);
      }
    }
  } catch (const DbError& e) {
    if (db_) db_->Rollback();
    if (e.kind() == DbErrorKind::kUnreachable) db_.reset();
    throw;
  } catch (...) {
    // Whatever failed, the open transaction must not survive: the next
    // START TRANSACTION would commit it half done.
    if (db_) db_->Rollback();
    throw;
  }
  return result;
}

void DbWriter::WriteRunAtomically(const std::vector<const Record*>& run, WriteResult* result) {
  bool check_present = false;
  bool force_insert = false;
  while (true) {
    try {
      WriteRun(run, check_present, force_insert, result);
      return;
    } catch (const ScratchFileError& e) {
      db_->Rollback();
      if (force_insert) throw;
      force_insert = true;
      ++scratch_failures_;
      const auto now = std::chrono::steady_clock::now();
      if (scratch_failures_ == 1 || now - last_scratch_notice_ > std::chrono::seconds(10)) {
        last_scratch_notice_ = now;
        notice_(std::string(e.what()) + "; the batch was rolled back and goes as multi-row "
                "INSERTs (" + std::to_string(scratch_failures_) + " batches so far)");
      }
    } catch (const DbError& e) {
      db_->Rollback();
      if (e.code() == kDuplicateKey && !check_present) {
        check_present = true;
      } else if (options_.method == InsertMethod::kAuto && IsLoadDataRefused(e.code()) &&
                 !load_data_refused_) {
        load_data_refused_ = true;
        notice_("server " + target_.Server() + " refuses LOAD DATA LOCAL (" + e.cause() +
                "); using multi-row INSERTs only");
      } else {
        throw;
      }
    }
  }
}

bool DbWriter::LoadSimulation(const std::string& where, SimInfo* info) {
  std::unique_ptr<sql::ResultSet> rows = db_->Query(
      "SELECT simulationID, busSimulationID, stateEvery, logInterval FROM Simulation WHERE " +
          where + " ORDER BY simulationID DESC LIMIT 1",
      "SELECT FROM Simulation");
  try {
    if (!rows->next()) return false;
    info->id = rows->getUInt(1);
    info->bus_id = rows->getInt64(2);
    info->stride = std::lcm(std::max(1, rows->getInt(3)), std::max(1, rows->getInt(4)));
  } catch (const sql::SQLException&) {
    db_->Rethrow("read Simulation");
  }
  const std::string id = std::to_string(info->id);
  info->last_step = LastLoggedStep(db_.get(), info->id);
  const auto count = [&](const char* table) {
    return static_cast<size_t>(db_->QueryInt(
        std::string("SELECT COUNT(*) FROM ") + table + " WHERE simulationID = " + id,
        std::string("SELECT COUNT(*) FROM ") + table, 0));
  };
  info->robot_ids = LoadIds("Robot", "robotID", info->id, count("Robot"));
  info->body_ids = LoadIds("Body", "bodyID", info->id, count("Body"));
  info->joint_ids = LoadIds("`Joint`", "jointID", info->id, count("`Joint`"));
  info->sensor_ids = LoadIds("Sensor", "sensorID", info->id, count("Sensor"));
  return true;
}

std::vector<int64_t> DbWriter::LoadIds(const char* table, const char* id_column,
                                       uint32_t simulation, size_t count) {
  std::vector<int64_t> ids(count, -1);
  std::unique_ptr<sql::ResultSet> rows =
      db_->Query(std::string("SELECT busIndex, ") + id_column + " FROM " + table +
                     " WHERE simulationID = " + std::to_string(simulation),
                 std::string("SELECT FROM ") + table);
  try {
    while (rows->next()) {
      const int64_t index = rows->getInt64(1);
      if (index >= 0 && index < static_cast<int64_t>(count))
        ids[static_cast<size_t>(index)] = rows->getInt64(2);
    }
  } catch (const sql::SQLException&) {
    db_->Rethrow(std::string("read ") + table);
  }
  return ids;
}

InsertMethod DbWriter::MethodFor(size_t steps) const {
  if (options_.method != InsertMethod::kAuto) return options_.method;
  return steps >= kLoadDataMinSteps && !load_data_refused_ ? InsertMethod::kLoadDataLocal
                                                           : InsertMethod::kMultiRowInsert;
}

DbWriter::SimInfo* DbWriter::FindSimulation(int64_t bus_id) {
  auto it = simulations_.find(bus_id);
  if (it != simulations_.end()) return &it->second;
  SimInfo info;
  if (!LoadSimulation("busSimulationID = " + std::to_string(bus_id), &info)) return nullptr;
  // Records of a simulation logged before (a replayed spool, a restarted
  // logger) before its model came by again.
  notice_("resuming simulation " + std::to_string(info.id) + " (bus simulation id " +
          std::to_string(bus_id) + ", last logged step " + std::to_string(info.last_step) + ")");
  return &simulations_.emplace(bus_id, std::move(info)).first->second;
}

void DbWriter::CloseOthers(const SimInfo& keep, const std::string& host, const std::string& reason) {
  std::vector<uint32_t> open;
  std::unique_ptr<sql::ResultSet> rows = db_->Query(
      "SELECT simulationID FROM Simulation WHERE endTime IS NULL AND host = " + Quoted(host) +
          " AND lcmUrl = " + Quoted(options_.lcm_url) +
          " AND simulationID <> " + std::to_string(keep.id),
      "SELECT open simulations FROM Simulation");
  try {
    while (rows->next()) open.push_back(rows->getUInt(1));
  } catch (const sql::SQLException&) {
    db_->Rethrow("read Simulation");
  }
  for (uint32_t id : open) {
    const std::string sid = std::to_string(id);
    db_->Execute("UPDATE Simulation SET endTime = UTC_TIMESTAMP(6), endReason = " + Quoted(reason) +
                     ", lastStep = (SELECT MAX(step) FROM SimulationRow WHERE simulationID = " +
                     sid + ") WHERE simulationID = " + sid + " AND endTime IS NULL",
                 "UPDATE Simulation (close " + sid + ")");
    notice_("closed simulation " + sid + ": " + reason);
  }
}

void DbWriter::WriteModel(const Record& record, WriteResult* result) {
  model_t model;
  if (!DecodeRecord(record, &model, notice_)) {
    ++result->unwritable;
    return;
  }
  auto cached = simulations_.find(model.simulation_id);
  if (cached != simulations_.end()) return;  // announced again

  SimInfo info;
  db_->Begin();
  const bool resumed = LoadSimulation("busSimulationID = " + std::to_string(model.simulation_id) +
                                          " AND host = " + Quoted(model.host),
                                      &info);
  if (!resumed) {
    const int stride = std::lcm(std::max(1, model.state_every), std::max(1, options_.log_interval));
    std::string sql =
        "INSERT INTO Simulation (busSimulationID, host, lcmUrl, startTime, worldFile, worldName, "
        "parameters, stepSize, stateEvery, logInterval, gravityX, gravityY, gravityZ) VALUES (";
    AppendInt(&sql, model.simulation_id);
    sql += "," + Quoted(model.host) + "," + Quoted(options_.lcm_url) + "," +
           UtcFromMicros(record.received_us) + "," + Quoted(model.world_file) + "," +
           Quoted(model.world_name) + "," + Quoted(model.parameters) + ",";
    AppendDouble(&sql, model.step_size);
    sql += "," + std::to_string(model.state_every) + "," + std::to_string(options_.log_interval);
    for (double g : model.gravity) {
      sql += ",";
      AppendDouble(&sql, g);
    }
    sql += ")";
    db_->Execute(sql, "INSERT INTO Simulation");
    info.id = static_cast<uint32_t>(
        db_->QueryInt("SELECT LAST_INSERT_ID()", "SELECT LAST_INSERT_ID()", 0));
    info.bus_id = model.simulation_id;
    info.stride = stride;
    info.last_step = -1;
    const std::string sid = std::to_string(info.id);

    if (!model.robots.empty()) {
      RowSink robots(db_.get(), InsertMethod::kMultiRowInsert, "", "Robot",
                     "simulationID,busIndex,name,model,file,totalMass");
      for (size_t i = 0; i < model.robots.size(); ++i) {
        const robot_t& r = model.robots[i];
        robots.BeginRow();
        robots.Int(info.id);
        robots.Int(static_cast<int64_t>(i));
        robots.Text(r.name);
        robots.Text(r.model);
        robots.Text(r.file);
        robots.Double(r.total_mass);
        robots.EndRow();
      }
      robots.Finish();
    }
    info.robot_ids = LoadIds("Robot", "robotID", info.id, model.robots.size());

    if (!model.materials.empty()) {
      RowSink materials(db_.get(), InsertMethod::kMultiRowInsert, "", "Material",
                        "simulationID,busIndex,name,mu,mu2,frictionDirection,bounce,"
                        "bounceVelocity,softERP,softCFM,stiffness,damping,rollingFriction");
      constexpr double kNull = std::numeric_limits<double>::quiet_NaN();
      for (size_t i = 0; i < model.materials.size(); ++i) {
        const material_t& m = model.materials[i];
        const bool physical = m.stiffness > 0.0;
        materials.BeginRow();
        materials.Int(info.id);
        materials.Int(static_cast<int64_t>(i));
        materials.Text(m.name);
        materials.Double(m.mu);
        materials.Double(m.mu2);
        materials.Text(m.friction_direction == material_t::FRICTION_ROLLING ? "ROLLING" : "SLIP");
        materials.Double(m.bounce);
        materials.Double(m.bounce_velocity);
        materials.Double(physical ? kNull : m.soft_erp);
        materials.Double(physical ? kNull : m.soft_cfm);
        materials.Double(physical ? m.stiffness : kNull);
        materials.Double(physical ? m.damping : kNull);
        materials.Double(m.rolling_friction);
        materials.EndRow();
      }
      materials.Finish();
    }
    const std::vector<int64_t> material_ids =
        LoadIds("Material", "materialID", info.id, model.materials.size());
    auto material_index = [&model](const std::string& name) -> int64_t {
      for (size_t i = 0; i < model.materials.size(); ++i)
        if (model.materials[i].name == name) return static_cast<int64_t>(i);
      return -1;  // "" (the default material): NULL
    };

    if (!model.bodies.empty()) {
      RowSink bodies(db_.get(), InsertMethod::kMultiRowInsert, "", "Body",
                     "simulationID,robotID,busIndex,name,type,dimX,dimY,dimZ,mass,comX,comY,comZ,"
                     "Ixx,Iyy,Izz,Ixy,Ixz,Iyz,material,materialID,isStatic");
      for (size_t i = 0; i < model.bodies.size(); ++i) {
        const body_t& b = model.bodies[i];
        bodies.BeginRow();
        bodies.Int(info.id);
        bodies.Id(info.robot_ids, b.robot);
        bodies.Int(static_cast<int64_t>(i));
        bodies.Text(b.name);
        bodies.Text(GeometryName(b.geometry.kind));
        for (double d : b.geometry.size) bodies.Double(d);
        bodies.Double(b.mass);
        for (double c : b.com) bodies.Double(c);
        for (double in : b.inertia) bodies.Double(in);
        bodies.Text(b.material);
        bodies.Id(material_ids, material_index(b.material));
        bodies.Int(b.is_static ? 1 : 0);
        bodies.EndRow();
      }
      bodies.Finish();
    }
    info.body_ids = LoadIds("Body", "bodyID", info.id, model.bodies.size());

    if (!model.joints.empty()) {
      RowSink joints(db_.get(), InsertMethod::kMultiRowInsert, "", "`Joint`",
                     "simulationID,robotID,busIndex,name,type,body1ID,body2ID,numAxes,anchorX,"
                     "anchorY,anchorZ,axis1X,axis1Y,axis1Z,axis2X,axis2Y,axis2Z,axis3X,axis3Y,"
                     "axis3Z,loStop1,hiStop1,loStop2,hiStop2,loStop3,hiStop3");
      for (size_t i = 0; i < model.joints.size(); ++i) {
        const joint_t& j = model.joints[i];
        joints.BeginRow();
        joints.Int(info.id);
        joints.Id(info.robot_ids, j.robot);
        joints.Int(static_cast<int64_t>(i));
        joints.Text(j.name);
        joints.Text(JointName(j.kind));
        joints.Id(info.body_ids, j.body1);
        joints.Id(info.body_ids, j.body2);
        joints.Int(j.num_axes);
        for (double a : j.anchor) joints.Double(a);
        for (const auto& axis : j.axis)
          for (double a : axis) joints.Double(a);
        for (int a = 0; a < 3; ++a) {
          joints.Double(j.lo_stop[a]);  // +-inf (free) becomes NULL
          joints.Double(j.hi_stop[a]);
        }
        joints.EndRow();
      }
      joints.Finish();
    }
    info.joint_ids = LoadIds("`Joint`", "jointID", info.id, model.joints.size());

    if (!model.sensors.empty()) {
      RowSink sensors(db_.get(), InsertMethod::kMultiRowInsert, "", "Sensor",
                      "simulationID,robotID,busIndex,name,type,bodyID,jointID,port,rate,params");
      for (size_t i = 0; i < model.sensors.size(); ++i) {
        const sensor_t& s = model.sensors[i];
        sensors.BeginRow();
        sensors.Int(info.id);
        sensors.Id(info.robot_ids, s.robot);
        sensors.Int(static_cast<int64_t>(i));
        sensors.Text(s.name);
        sensors.Text(SensorName(s.kind));
        sensors.Id(info.body_ids, s.body);
        sensors.Id(info.joint_ids, s.joint);
        sensors.Int(s.port);
        sensors.Double(s.rate);
        sensors.Text(JoinValues(s.params));
        sensors.EndRow();
      }
      sensors.Finish();
    }
    info.sensor_ids = LoadIds("Sensor", "sensorID", info.id, model.sensors.size());

    std::vector<int64_t> actuator_ids;
    if (!model.actuators.empty()) {
      RowSink actuators(db_.get(), InsertMethod::kMultiRowInsert, "", "Actuator",
                        "simulationID,robotID,busIndex,name,type,jointID,port");
      for (size_t i = 0; i < model.actuators.size(); ++i) {
        const actuator_t& a = model.actuators[i];
        actuators.BeginRow();
        actuators.Int(info.id);
        actuators.Id(info.robot_ids, a.robot);
        actuators.Int(static_cast<int64_t>(i));
        actuators.Text(a.name);
        actuators.Text(ActuatorName(a.kind));
        actuators.Id(info.joint_ids, a.joint);
        actuators.Int(a.port);
        actuators.EndRow();
      }
      actuators.Finish();
      actuator_ids = LoadIds("Actuator", "actuatorID", info.id, model.actuators.size());
    }

    // RobotComponent: what each robot is made of, by name.
    RowSink components(db_.get(), InsertMethod::kMultiRowInsert, "", "RobotComponent",
                       "robotID,type,name,reference");
    auto component = [&](int16_t robot, const char* type, const std::string& name,
                         const std::vector<int64_t>& ids, size_t index) {
      if (robot < 0 || robot >= static_cast<int16_t>(info.robot_ids.size())) return;
      components.BeginRow();
      components.Int(info.robot_ids[static_cast<size_t>(robot)]);
      components.Text(type);
      components.Text(name);
      components.Int(ids[index]);
      components.EndRow();
    };
    for (size_t i = 0; i < model.bodies.size(); ++i)
      component(model.bodies[i].robot, "BODY", model.bodies[i].name, info.body_ids, i);
    for (size_t i = 0; i < model.joints.size(); ++i)
      component(model.joints[i].robot, "JOINT", model.joints[i].name, info.joint_ids, i);
    for (size_t i = 0; i < model.sensors.size(); ++i)
      component(model.sensors[i].robot, "SENSOR", model.sensors[i].name, info.sensor_ids, i);
    for (size_t i = 0; i < model.actuators.size(); ++i)
      component(model.actuators[i].robot, "ACTUATOR", model.actuators[i].name, actuator_ids, i);
    components.Finish();
  }
  // Closed as silent by a logger before this one, but its sim talks: open
  // again (steps lost meanwhile show as a gap when states come).
  bool reopened = false;
  if (resumed) {
    db_->Execute("UPDATE Simulation SET endTime = NULL, endReason = NULL, lastStep = NULL"
                 " WHERE simulationID = " + std::to_string(info.id) + " AND endReason LIKE " +
                 Quoted(std::string(kSilentReasonStart) + "%"),
                 "UPDATE Simulation (reopen " + std::to_string(info.id) + ")");
    reopened = db_->QueryInt("SELECT ROW_COUNT()", "SELECT ROW_COUNT()", 0) > 0;
  }
  CloseOthers(info, model.host,
              "a new simulation started on the bus (the sim restarted or was reset)");
  db_->Commit();
  if (reopened)
    notice_("reopened simulation " + std::to_string(info.id) +
            ": its sim announced its model again after it was closed as silent");
  notice_(std::string(resumed ? "resuming" : "logging") + " simulation " +
          std::to_string(info.id) + " (bus simulation id " + std::to_string(model.simulation_id) +
          " from " + model.host + ", world '" + model.world_name + "', " +
          std::to_string(model.bodies.size()) + " bodies, " + std::to_string(model.joints.size()) +
          " joints" +
          (resumed ? ", last logged step " + std::to_string(info.last_step) : std::string()) + ")");
  simulations_[model.simulation_id] = std::move(info);
}

void DbWriter::CloseSimulation(const Record& record) {
  SimInfo* sim = FindSimulation(record.simulation_id);
  if (sim == nullptr) return;
  const EndedPayload ended = ReadEnded(record);
  const std::string sid = std::to_string(sim->id);
  const std::string reason =
      ended.reason.empty() ? std::string("the sim stopped") : ColumnText(ended.reason, 255);
  const std::string logged = "(SELECT MAX(step) FROM SimulationRow WHERE simulationID = " + sid + ")";
  // A sim that went silent ends at the last step seen (a step refused
  // after it was received is in LogGap, not in SimulationRow).
  const std::string last_step =
      ended.kind == EndKind::kSilent
          ? "GREATEST(COALESCE(" + logged + ", -1), " + std::to_string(ended.last_step) + ")"
          : logged;
  db_->Execute("UPDATE Simulation SET endTime = UTC_TIMESTAMP(6), endReason = " + Quoted(reason) +
                   ", lastStep = " + last_step + " WHERE simulationID = " + sid +
                   " AND endTime IS NULL",
               "UPDATE Simulation (close " + sid + ")");
  if (db_->QueryInt("SELECT ROW_COUNT()", "SELECT ROW_COUNT()", 0) == 0) return;  // closed before
  notice_("closed simulation " + sid + ": " + reason +
          (ended.kind == EndKind::kStopped
               ? " at step " + std::to_string(ended.last_step)
               : std::string()));
}

void DbWriter::ReopenSimulation(const Record& record) {
  SimInfo* sim = FindSimulation(record.simulation_id);
  if (sim == nullptr) return;
  const std::string sid = std::to_string(sim->id);
  // Open again as if it had never closed: a reader takes endTime NULL as
  // running; lastStep is set again when it closes.
  db_->Execute("UPDATE Simulation SET endTime = NULL, endReason = NULL, lastStep = NULL"
               " WHERE simulationID = " + sid + " AND endTime IS NOT NULL",
               "UPDATE Simulation (reopen " + sid + ")");
  if (db_->QueryInt("SELECT ROW_COUNT()", "SELECT ROW_COUNT()", 0) == 0) return;  // open already
  notice_("reopened simulation " + sid + ": " + ReadReopened(record));
}

void DbWriter::WriteRun(const std::vector<const Record*>& run, bool check_present,
                        bool force_insert, WriteResult* result) {
  // States and gap records by simulation, in arrival order.
  struct Item {
    state_t state;
    bool is_gap = false;
    GapPayload gap;
  };
  std::map<int64_t, std::vector<Item>> items;
  std::vector<const Record*> others;
  uint64_t undecodable = 0;
  for (const Record* r : run) {
    if (FindSimulation(r->simulation_id) == nullptr) {
      ++result->unwritable;
      notice_(std::string("a ") + RecordKindName(r->kind) + " of bus simulation " +
              std::to_string(r->simulation_id) +
              " has no Simulation row (its SIM_MODEL never reached the database); not written");
      continue;
    }
    if (r->kind == RecordKind::kState) {
      Item item;
      if (!DecodeRecord(*r, &item.state, notice_)) {
        ++undecodable;
        continue;
      }
      items[r->simulation_id].push_back(std::move(item));
    } else if (r->kind == RecordKind::kGap) {
      Item item;
      item.is_gap = true;
      item.gap = ReadGap(*r);
      items[r->simulation_id].push_back(std::move(item));
    } else {
      others.push_back(r);
    }
  }
  if (items.empty() && others.empty()) return;

  db_->Begin();
  std::vector<int64_t> published;  // publish times of the states written
  std::map<int64_t, int64_t> new_last_step;
  WriteResult pending;
  pending.unwritable = undecodable;
  for (auto& [bus_id, list] : items) {
    SimInfo* sim = FindSimulation(bus_id);
    const std::string sid = std::to_string(sim->id);
    bool any_state = false;
    int64_t lo = 0, hi = 0;
    size_t bodies = 0, joints = 0;
    for (const Item& item : list) {
      if (item.is_gap) continue;
      const int64_t step = item.state.step;
      if (!any_state) {
        lo = hi = step;
        bodies = item.state.bodies.size();
        joints = item.state.joints.size();
      }
      any_state = true;
      lo = std::min(lo, step);
      hi = std::max(hi, step);
    }
    const std::string range = " WHERE simulationID = " + sid + " AND step BETWEEN " +
                              std::to_string(lo) + " AND " + std::to_string(hi);
    // Steps already in the database with all their rows, and steps whose
    // SimulationRow is there without all of its rows (left by a logger
    // before transactions covered every failure): those get their rows.
    std::set<int64_t> present;
    std::unordered_map<int64_t, int64_t> incomplete;  // step -> simulationRowID
    if (any_state && (check_present || lo <= sim->last_step)) {
      std::unique_ptr<sql::ResultSet> rows = db_->Query(
          "SELECT r.step, r.simulationRowID,"
          " (SELECT COUNT(*) FROM Pose p WHERE p.simulationRowID = r.simulationRowID),"
          " (SELECT COUNT(*) FROM ForceAndTorque f WHERE f.simulationRowID = r.simulationRowID),"
          " (SELECT COUNT(*) FROM JointPose j WHERE j.simulationRowID = r.simulationRowID)"
          " FROM SimulationRow r" + range,
          "SELECT step FROM SimulationRow");
      try {
        while (rows->next()) {
          const int64_t step = rows->getInt64(1);
          if (rows->getUInt64(3) == bodies && rows->getUInt64(4) == bodies &&
              rows->getUInt64(5) == joints)
            present.insert(step);
          else
            incomplete[step] = static_cast<int64_t>(rows->getUInt64(2));
        }
      } catch (const sql::SQLException&) {
        db_->Rethrow("read SimulationRow");
      }
    }
    std::vector<const state_t*> fresh;
    std::vector<const state_t*> repaired;
    int64_t last = sim->last_step;
    RowSink gaps(db_.get(), InsertMethod::kMultiRowInsert, "", "LogGap",
                 "simulationID,firstStep,lastStep,missing,detectedAt,reason",
                 "lastStep = VALUES(lastStep), missing = VALUES(missing), reason = VALUES(reason)");
    auto gap_row = [&](int64_t first, int64_t last_missing, int64_t missing,
                       const std::string& reason) {
      gaps.BeginRow();
      gaps.Int(sim->id);
      gaps.Int(first);
      gaps.Int(last_missing);
      gaps.Int(missing);
      gaps.Expression("UTC_TIMESTAMP(6)");
      gaps.Text(ColumnText(reason, 255));
      gaps.EndRow();
      ++pending.gaps;
      pending.missing_steps += static_cast<uint64_t>(missing);
    };
    for (const Item& item : list) {
      if (item.is_gap) {
        // Steps the receiver had but could not keep; any steps before them
        // that never came are a gap of their own.
        const GapPayload& g = item.gap;
        if (last >= 0 && g.first_step > last + sim->stride)
          gap_row(last + sim->stride, g.first_step - sim->stride,
                  (g.first_step - last) / sim->stride - 1, kGapNotReceived);
        if (g.last_step > last) {
          gap_row(g.first_step, g.last_step, g.missing, g.reason);
          last = g.last_step;
        }
        continue;
      }
      const state_t& s = item.state;
      if (last >= 0 && s.step > last + sim->stride)
        gap_row(last + sim->stride, s.step - sim->stride, (s.step - last) / sim->stride - 1,
                kGapNotReceived);
      last = std::max(last, s.step);
      if (!present.insert(s.step).second) {
        ++pending.states_present;
        continue;
      }
      if (incomplete.count(s.step) > 0) repaired.push_back(&s);
      else fresh.push_back(&s);
    }
    gaps.Finish();
    pending.rows_written += gaps.rows();
    new_last_step[bus_id] = last;
    if (fresh.empty() && repaired.empty()) continue;

    std::unordered_map<int64_t, int64_t> row_ids = incomplete;
    RowSink steps(db_.get(), InsertMethod::kMultiRowInsert, "", "SimulationRow",
                  "simulationID,step,simulationTime,publishedUtime");
    if (!fresh.empty()) {
      for (const state_t* s : fresh) {
        steps.BeginRow();
        steps.Int(sim->id);
        steps.Int(s->step);
        steps.Double(s->sim_time);
        steps.Int(s->utime);
        steps.EndRow();
      }
      steps.Finish();
      std::unique_ptr<sql::ResultSet> rows = db_->Query(
          "SELECT step, simulationRowID FROM SimulationRow" + range, "SELECT FROM SimulationRow");
      try {
        while (rows->next()) row_ids[rows->getInt64(1)] = static_cast<int64_t>(rows->getUInt64(2));
      } catch (const sql::SQLException&) {
        db_->Rethrow("read SimulationRow");
      }
    }
    // The per-step rows of a list of states, into one sink per table.
    auto write_rows = [&](const std::vector<const state_t*>& states, InsertMethod method,
                          bool keep_existing) {
      const std::string poses_dup = keep_existing ? "x = x" : "";
      const std::string forces_dup = keep_existing ? "F_x = F_x" : "";
      const std::string joints_dup = keep_existing ? "angle = angle" : "";
      RowSink poses(db_.get(), method, options_.scratch_dir, "Pose",
                    "simulationRowID,bodyID,x,y,z,axisX,axisY,axisZ,angle", poses_dup);
      RowSink forces(db_.get(), method, options_.scratch_dir, "ForceAndTorque",
                     "simulationRowID,bodyID,F_x,F_y,F_z,T_x,T_y,T_z", forces_dup);
      RowSink joint_rows(db_.get(), method, options_.scratch_dir, "JointPose",
                         "simulationRowID,jointID,anchorx,anchory,anchorz,angle,angle2,angle3,rate,"
                         "rate2,rate3,F_x,F_y,F_z,T_x,T_y,T_z,continuousAngle,continuousAngle2,"
                         "continuousAngle3",
                         joints_dup);
      for (const state_t* s : states) {
        const int64_t row = row_ids.at(s->step);
        for (size_t b = 0; b < s->bodies.size(); ++b) {
          const body_state_t& body = s->bodies[b];
          const AxisAngle aa = AxisAngleFromQuaternion(body.orientation);
          poses.BeginRow();
          poses.Int(row);
          poses.Int(sim->body_ids[b]);
          for (double p : body.position) poses.Double(p);
          for (double a : aa.axis) poses.Double(a);
          poses.Double(aa.angle);
          poses.EndRow();
          forces.BeginRow();
          forces.Int(row);
          forces.Int(sim->body_ids[b]);
          for (double f : body.contact_force) forces.Double(f);
          for (double t : body.contact_torque) forces.Double(t);
          forces.EndRow();
        }
        for (size_t j = 0; j < s->joints.size(); ++j) {
          const joint_state_t& joint = s->joints[j];
          joint_rows.BeginRow();
          joint_rows.Int(row);
          joint_rows.Int(sim->joint_ids[j]);
          for (double a : joint.anchor) joint_rows.Double(a);
          for (double p : joint.position) joint_rows.Double(p);
          for (double r : joint.rate) joint_rows.Double(r);
          for (double f : joint.force1) joint_rows.Double(f);
          for (double t : joint.torque1) joint_rows.Double(t);
          for (double p : joint.continuous_position) joint_rows.Double(p);
          joint_rows.EndRow();
        }
        published.push_back(s->utime);
      }
      poses.Finish();
      forces.Finish();
      joint_rows.Finish();
      return poses.rows() + forces.rows() + joint_rows.rows();
    };
    uint64_t rows = steps.rows();
    if (!fresh.empty())
      rows += write_rows(fresh, force_insert ? InsertMethod::kMultiRowInsert : MethodFor(fresh.size()),
                         false);
    if (!repaired.empty()) {
      rows += write_rows(repaired, InsertMethod::kMultiRowInsert, true);
      pending.states_repaired += repaired.size();
    }
    pending.states_written += fresh.size() + repaired.size();
    pending.rows_written += rows;
  }

  // Sensor readings, commands and replies: few, keyed so a replay is a no-op.
  RowSink readings(db_.get(), InsertMethod::kMultiRowInsert, "", "SensorReading",
                   "simulationID,sensorID,step,simulationTime,receivedUtime,vals,text",
                   "step = step");
  RowSink commands(db_.get(), InsertMethod::kMultiRowInsert, "", "Command",
                   "simulationID,meantForBusSimulationID,receivedUtime,sentUtime,sender,requestID,"
                   "robot,target,port,action,applyAtStep,vals,text",
                   "requestID = requestID");
  RowSink replies(db_.get(), InsertMethod::kMultiRowInsert, "", "CommandReply",
                  "simulationID,receivedUtime,sender,requestID,target,accepted,reason,"
                  "appliedAtStep,previous,previousText",
                  "requestID = requestID");
  for (const Record* r : others) {
    const SimInfo* sim = FindSimulation(r->simulation_id);
    if (r->kind == RecordKind::kSensor) {
      sensor_reading_t reading;
      if (!DecodeRecord(*r, &reading, notice_)) continue;
      if (reading.sensor < 0 || reading.sensor >= static_cast<int32_t>(sim->sensor_ids.size()))
        continue;  // the receiver checks this against the model
      readings.BeginRow();
      readings.Int(sim->id);
      readings.Int(sim->sensor_ids[static_cast<size_t>(reading.sensor)]);
      readings.Int(reading.step);
      readings.Double(reading.sim_time);
      readings.Int(r->received_us);
      readings.Text(JoinValues(reading.values));
      readings.Text(reading.text);
      readings.EndRow();
    } else if (r->kind == RecordKind::kCommand) {
      command_t c;
      if (!DecodeRecord(*r, &c, notice_)) continue;
      commands.BeginRow();
      commands.Int(sim->id);
      commands.Int(c.simulation_id);
      commands.Int(r->received_us);
      commands.Int(c.utime);
      commands.Text(c.sender);
      commands.Int(c.request_id);
      commands.Text(c.robot);
      commands.Text(c.target);
      commands.Int(c.port);
      commands.Text(SpellAction(c.action).database);
      commands.Int(c.apply_at_step);
      commands.Text(JoinValues(c.values));
      commands.Text(c.text);
      commands.EndRow();
    } else if (r->kind == RecordKind::kCommandReply) {
      command_reply_t c;
      if (!DecodeRecord(*r, &c, notice_)) continue;
      replies.BeginRow();
      replies.Int(sim->id);
      replies.Int(r->received_us);
      replies.Text(c.sender);
      replies.Int(c.request_id);
      replies.Text(c.target);
      replies.Int(c.accepted ? 1 : 0);
      replies.Text(c.reason);
      replies.Int(c.applied_at_step);
      replies.Text(JoinValues(c.previous));
      replies.Text(c.previous_text);
      replies.EndRow();
    }
  }
  readings.Finish();
  commands.Finish();
  replies.Finish();
  pending.rows_written += readings.rows() + commands.rows() + replies.rows();

  db_->Commit();
  const int64_t committed = NowMicros();
  for (const auto& [bus_id, last] : new_last_step) simulations_[bus_id].last_step = last;
  result->states_written += pending.states_written;
  result->states_present += pending.states_present;
  result->rows_written += pending.rows_written;
  result->gaps += pending.gaps;
  result->missing_steps += pending.missing_steps;
  result->states_repaired += pending.states_repaired;
  result->unwritable += pending.unwritable;
  for (int64_t p : published) result->lags_us.push_back(committed - p);
}

}  // namespace simpartner::logger
