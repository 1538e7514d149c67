#include "simpartner/logger/schema.h"

#include <cctype>
#include <sstream>

#include "simpartner/logger/sql_text.h"
#include "simpartner/sensor_kinds.h"

namespace simpartner::logger {
namespace {

// "FORCE_TORQUE" -> "ForceTorqueReading": the view of one kind's readings.
std::string ReadingViewName(const std::string& database_name) {
  std::string name;
  bool upper = true;
  for (const char c : database_name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    name += upper ? c : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    upper = false;
  }
  return name + "Reading";
}

// A view per sensor kind over SensorReading, its values in named columns
// (sensor_kinds.h; a Scanner's and a Lidar's ranges stay one text,
// layer-major), so SQL reads `SELECT az FROM ImuReading` rather than
// splitting `vals`. Views, not tables: the readings are stored once.
std::vector<std::string> ReadingViews() {
  std::vector<std::string> views;
  for (const SensorKindSpelling& kind : SensorKindSpellings()) {
    const std::string columns = kind.columns;
    if (columns.empty()) continue;  // Echo (text), Camera (images)
    std::string select =
        "CREATE VIEW IF NOT EXISTS " + ReadingViewName(kind.database) +
        " AS SELECT r.simulationID, r.sensorID, s.name AS sensor, r.step, r.simulationTime";
    if (columns == "range") {
      select += ", r.vals AS ranges";
    } else {
      std::istringstream names(columns);
      std::string name;
      for (int k = 1; names >> name; ++k)
        select += ", CAST(SUBSTRING_INDEX(SUBSTRING_INDEX(r.vals, ',', " + std::to_string(k) +
                  "), ',', -1) AS DOUBLE) AS `" + name + "`";
    }
    views.push_back(select + " FROM SensorReading r JOIN Sensor s ON s.sensorID = r.sensorID WHERE "
                             "s.type = '" + kind.database + "'");
  }
  return views;
}

constexpr const char* kTableOptions = " ENGINE=InnoDB DEFAULT CHARSET=utf8mb4";

std::vector<Migration> BuildMigrations() {
  std::vector<Migration> m;
  m.push_back(Migration{
      1,
      "simulations, robots, bodies, joints, sensors, actuators and the per-step tables "
      "SimulationRow, Pose, JointPose, ForceAndTorque, LogGap",
      {
          std::string("CREATE TABLE IF NOT EXISTS Simulation ("
                      " simulationID INT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " busSimulationID BIGINT NOT NULL COMMENT 'model_t.simulation_id: new for every start or reset of the sim',"
                      " host VARCHAR(255) NOT NULL COMMENT 'host of the sim process',"
                      " lcmUrl VARCHAR(255) NOT NULL COMMENT 'bus the logger listened on',"
                      " startTime DATETIME(6) NOT NULL COMMENT 'UTC, when logging of this simulation began',"
                      " endTime DATETIME(6) NULL COMMENT 'UTC, when the sim stopped or another one replaced it; NULL while open',"
                      " endReason VARCHAR(255) NULL,"
                      " lastStep BIGINT NULL COMMENT 'last logged step, set when closed',"
                      " worldFile VARCHAR(1024) NOT NULL,"
                      " worldName VARCHAR(255) NOT NULL,"
                      " parameters TEXT NOT NULL COMMENT 'effective key=value lines of the sim',"
                      " stepSize DOUBLE NOT NULL COMMENT '[s]',"
                      " stateEvery INT NOT NULL COMMENT 'the sim published every Nth step',"
                      " logInterval INT NOT NULL COMMENT 'the logger kept every Nth published step',"
                      " gravityX DOUBLE NOT NULL COMMENT '[m/s^2]',"
                      " gravityY DOUBLE NOT NULL COMMENT '[m/s^2]',"
                      " gravityZ DOUBLE NOT NULL COMMENT '[m/s^2]',"
                      " PRIMARY KEY (simulationID),"
                      " UNIQUE KEY bus (busSimulationID, host)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS Robot ("
                      " robotID INT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " busIndex SMALLINT NOT NULL COMMENT 'index in model_t.robots',"
                      " name VARCHAR(255) NOT NULL,"
                      " model VARCHAR(255) NOT NULL,"
                      " file VARCHAR(1024) NOT NULL,"
                      " totalMass DOUBLE NOT NULL COMMENT '[kg]',"
                      " PRIMARY KEY (robotID),"
                      " UNIQUE KEY bus (simulationID, busIndex)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS Body ("
                      " bodyID INT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " robotID INT UNSIGNED NULL COMMENT 'NULL for a world object',"
                      " busIndex INT NOT NULL COMMENT 'index in model_t.bodies and state_t.bodies',"
                      " name VARCHAR(255) NOT NULL,"
                      " type VARCHAR(16) NOT NULL COMMENT 'NONE (point mass), BOX, SPHERE, CYLINDER, CAPSULE',"
                      " dimX DOUBLE NOT NULL COMMENT '[m] box: lx; sphere, cylinder, capsule: radius',"
                      " dimY DOUBLE NOT NULL COMMENT '[m] box: ly; cylinder, capsule: length',"
                      " dimZ DOUBLE NOT NULL COMMENT '[m] box: lz',"
                      " mass DOUBLE NOT NULL COMMENT '[kg]',"
                      " comX DOUBLE NOT NULL COMMENT '[m] centre of mass, body frame',"
                      " comY DOUBLE NOT NULL,"
                      " comZ DOUBLE NOT NULL,"
                      " Ixx DOUBLE NOT NULL COMMENT '[kg m^2] about the centre of mass, body axes',"
                      " Iyy DOUBLE NOT NULL,"
                      " Izz DOUBLE NOT NULL,"
                      " Ixy DOUBLE NOT NULL,"
                      " Ixz DOUBLE NOT NULL,"
                      " Iyz DOUBLE NOT NULL,"
                      " material VARCHAR(255) NOT NULL,"
                      " isStatic TINYINT NOT NULL,"
                      " PRIMARY KEY (bodyID),"
                      " UNIQUE KEY bus (simulationID, busIndex),"
                      " KEY name (simulationID, name)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS `Joint` ("
                      " jointID INT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " robotID INT UNSIGNED NULL,"
                      " busIndex INT NOT NULL COMMENT 'index in model_t.joints and state_t.joints',"
                      " name VARCHAR(255) NOT NULL,"
                      " type VARCHAR(16) NOT NULL COMMENT 'FIXED, HINGE, SLIDER, BALL, UNIVERSAL, HINGE2',"
                      " body1ID INT UNSIGNED NULL COMMENT 'NULL = the static world',"
                      " body2ID INT UNSIGNED NULL COMMENT 'NULL = the static world',"
                      " numAxes TINYINT NOT NULL,"
                      " anchorX DOUBLE NOT NULL COMMENT '[m] world frame at step 0',"
                      " anchorY DOUBLE NOT NULL,"
                      " anchorZ DOUBLE NOT NULL,"
                      " axis1X DOUBLE NOT NULL, axis1Y DOUBLE NOT NULL, axis1Z DOUBLE NOT NULL,"
                      " axis2X DOUBLE NOT NULL, axis2Y DOUBLE NOT NULL, axis2Z DOUBLE NOT NULL,"
                      " axis3X DOUBLE NOT NULL, axis3Y DOUBLE NOT NULL, axis3Z DOUBLE NOT NULL,"
                      " loStop1 DOUBLE NULL COMMENT '[rad] or [m]; NULL = free',"
                      " hiStop1 DOUBLE NULL,"
                      " loStop2 DOUBLE NULL, hiStop2 DOUBLE NULL,"
                      " loStop3 DOUBLE NULL, hiStop3 DOUBLE NULL,"
                      " PRIMARY KEY (jointID),"
                      " UNIQUE KEY bus (simulationID, busIndex),"
                      " KEY name (simulationID, name)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS Sensor ("
                      " sensorID INT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " robotID INT UNSIGNED NULL,"
                      " busIndex INT NOT NULL COMMENT 'index in model_t.sensors',"
                      " name VARCHAR(255) NOT NULL,"
                      " type VARCHAR(16) NOT NULL COMMENT 'ECHO, POSITION, SCANNER, VELOCITY, FORCE_TORQUE, IMU, GNSS, ENCODER, LIDAR, CONTACT, CAMERA',"
                      " bodyID INT UNSIGNED NULL,"
                      " jointID INT UNSIGNED NULL,"
                      " port INT NOT NULL COMMENT 'legacy TCP port, 0 if none',"
                      " rate DOUBLE NOT NULL COMMENT '[Hz], 0 = on request',"
                      " params VARCHAR(1024) NOT NULL COMMENT 'scanner: rays, half-span [rad], range [m]',"
                      " PRIMARY KEY (sensorID),"
                      " UNIQUE KEY bus (simulationID, busIndex)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS Actuator ("
                      " actuatorID INT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " robotID INT UNSIGNED NULL,"
                      " busIndex INT NOT NULL COMMENT 'index in model_t.actuators',"
                      " name VARCHAR(255) NOT NULL,"
                      " type VARCHAR(24) NOT NULL COMMENT 'JOINT_VELOCITY, ANGLE, LINEAR_MOTOR',"
                      " jointID INT UNSIGNED NULL,"
                      " port INT NOT NULL COMMENT 'legacy TCP port, 0 if none',"
                      " PRIMARY KEY (actuatorID),"
                      " UNIQUE KEY bus (simulationID, busIndex)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS RobotComponent ("
                      " robotID INT UNSIGNED NOT NULL,"
                      " type ENUM('BODY','JOINT','SENSOR','ACTUATOR') NOT NULL,"
                      " name VARCHAR(255) NOT NULL,"
                      " reference INT UNSIGNED NOT NULL COMMENT 'bodyID, jointID, sensorID or actuatorID',"
                      " PRIMARY KEY (robotID, type, reference),"
                      " KEY name (robotID, name)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS SimulationRow ("
                      " simulationRowID BIGINT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " step BIGINT NOT NULL COMMENT 'steps since the sim started or reset',"
                      " simulationTime DOUBLE NOT NULL COMMENT '[s] = step x stepSize',"
                      " publishedUtime BIGINT NOT NULL COMMENT '[us] wall clock when the sim published the step',"
                      " PRIMARY KEY (simulationRowID),"
                      " UNIQUE KEY step (simulationID, step),"
                      " KEY time (simulationID, simulationTime)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS Pose ("
                      " simulationRowID BIGINT UNSIGNED NOT NULL,"
                      " bodyID INT UNSIGNED NOT NULL,"
                      " x DOUBLE NOT NULL COMMENT '[m] body frame origin, world frame',"
                      " y DOUBLE NOT NULL,"
                      " z DOUBLE NOT NULL,"
                      " axisX DOUBLE NOT NULL COMMENT 'unit rotation axis (body to world)',"
                      " axisY DOUBLE NOT NULL,"
                      " axisZ DOUBLE NOT NULL,"
                      " angle DOUBLE NOT NULL COMMENT '[rad] 0..pi',"
                      " PRIMARY KEY (simulationRowID, bodyID)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS ForceAndTorque ("
                      " simulationRowID BIGINT UNSIGNED NOT NULL,"
                      " bodyID INT UNSIGNED NOT NULL,"
                      " F_x DOUBLE NOT NULL COMMENT '[N] contact force on the body, world frame',"
                      " F_y DOUBLE NOT NULL,"
                      " F_z DOUBLE NOT NULL,"
                      " T_x DOUBLE NOT NULL COMMENT '[N m] contact torque about its centre of mass, world frame',"
                      " T_y DOUBLE NOT NULL,"
                      " T_z DOUBLE NOT NULL,"
                      " PRIMARY KEY (simulationRowID, bodyID)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS JointPose ("
                      " simulationRowID BIGINT UNSIGNED NOT NULL,"
                      " jointID INT UNSIGNED NOT NULL,"
                      " anchorx DOUBLE NOT NULL COMMENT '[m] world frame, on body1',"
                      " anchory DOUBLE NOT NULL,"
                      " anchorz DOUBLE NOT NULL,"
                      " angle DOUBLE NOT NULL COMMENT '[rad] or [m], axis 1 (body1 relative to body2)',"
                      " angle2 DOUBLE NOT NULL COMMENT 'axis 2 (0 if none)',"
                      " angle3 DOUBLE NOT NULL COMMENT 'axis 3 (0 if none)',"
                      " rate DOUBLE NOT NULL COMMENT '[rad/s] or [m/s], axis 1',"
                      " rate2 DOUBLE NOT NULL,"
                      " rate3 DOUBLE NOT NULL,"
                      " F_x DOUBLE NOT NULL COMMENT '[N] constraint force on body1, world frame',"
                      " F_y DOUBLE NOT NULL,"
                      " F_z DOUBLE NOT NULL,"
                      " T_x DOUBLE NOT NULL COMMENT '[N m] constraint torque on body1 about its centre of mass',"
                      " T_y DOUBLE NOT NULL,"
                      " T_z DOUBLE NOT NULL,"
                      " PRIMARY KEY (simulationRowID, jointID)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS LogGap ("
                      " simulationID INT UNSIGNED NOT NULL,"
                      " firstStep BIGINT NOT NULL COMMENT 'first step that never reached the database',"
                      " lastStep BIGINT NOT NULL,"
                      " missing BIGINT NOT NULL COMMENT 'logged steps missing in between',"
                      " detectedAt DATETIME(6) NOT NULL COMMENT 'UTC',"
                      " PRIMARY KEY (simulationID, firstStep)"
                      ")") + kTableOptions,
      }});
  m.push_back(Migration{
      2,
      "sensor readings, commands and command replies seen on the bus",
      {
          std::string("CREATE TABLE IF NOT EXISTS SensorReading ("
                      " sensorReadingID BIGINT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " sensorID INT UNSIGNED NOT NULL,"
                      " step BIGINT NOT NULL,"
                      " simulationTime DOUBLE NOT NULL COMMENT '[s]',"
                      " receivedUtime BIGINT NOT NULL COMMENT '[us] wall clock when the logger received it',"
                      " vals MEDIUMTEXT NOT NULL COMMENT 'comma-separated; units by Sensor.type (m, rad, m/s, N, N m)',"
                      " text TEXT NOT NULL,"
                      " PRIMARY KEY (sensorReadingID),"
                      " UNIQUE KEY reading (simulationID, sensorID, step, receivedUtime)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS Command ("
                      " commandID BIGINT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL COMMENT 'the simulation running when it was sent',"
                      " receivedUtime BIGINT NOT NULL COMMENT '[us]',"
                      " sentUtime BIGINT NOT NULL COMMENT '[us]',"
                      " sender VARCHAR(255) NOT NULL,"
                      " requestID BIGINT NOT NULL,"
                      " robot VARCHAR(255) NOT NULL,"
                      " target VARCHAR(255) NOT NULL,"
                      " port INT NOT NULL,"
                      " action VARCHAR(16) NOT NULL COMMENT 'SET, HOLD, SET_STOPS, SENSOR_PARAMS, READ',"
                      " applyAtStep BIGINT NOT NULL COMMENT '-1 = as soon as received',"
                      " vals TEXT NOT NULL COMMENT 'comma-separated',"
                      " text TEXT NOT NULL,"
                      " PRIMARY KEY (commandID),"
                      " UNIQUE KEY request (simulationID, sender(191), requestID, receivedUtime)"
                      ")") + kTableOptions,
          std::string("CREATE TABLE IF NOT EXISTS CommandReply ("
                      " commandReplyID BIGINT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " receivedUtime BIGINT NOT NULL COMMENT '[us]',"
                      " sender VARCHAR(255) NOT NULL COMMENT 'sender of the command',"
                      " requestID BIGINT NOT NULL,"
                      " target VARCHAR(255) NOT NULL,"
                      " accepted TINYINT NOT NULL,"
                      " reason TEXT NOT NULL,"
                      " appliedAtStep BIGINT NOT NULL COMMENT '-1 if rejected',"
                      " previous TEXT NOT NULL COMMENT 'comma-separated setting it replaced',"
                      " previousText TEXT NOT NULL,"
                      " PRIMARY KEY (commandReplyID),"
                      " UNIQUE KEY reply (simulationID, sender(191), requestID, receivedUtime)"
                      ")") + kTableOptions,
      }});
  m.push_back(Migration{
      3,
      "LogGap.reason: why the steps are missing (never received, or refused by the logger)",
      {
          std::string("ALTER TABLE LogGap ADD COLUMN IF NOT EXISTS reason VARCHAR(255) NOT NULL"
                      " DEFAULT 'never received (lost on the bus, or sent while no logger ran)'"
                      " COMMENT 'never received, or received but refused (the spool disk full)'"),
      }});
  m.push_back(Migration{
      4,
      "Material: each simulation's contact materials (mu and mu2, friction direction, "
      "softness per step or stiffness and damping); Body.materialID",
      {
          std::string("CREATE TABLE IF NOT EXISTS Material ("
                      " materialID INT UNSIGNED NOT NULL AUTO_INCREMENT,"
                      " simulationID INT UNSIGNED NOT NULL,"
                      " busIndex SMALLINT NOT NULL COMMENT 'index in model_t.materials',"
                      " name VARCHAR(255) NOT NULL,"
                      " mu DOUBLE NOT NULL COMMENT 'Coulomb friction along the first friction direction',"
                      " mu2 DOUBLE NOT NULL COMMENT 'across the first direction; equal to mu when isotropic',"
                      " frictionDirection VARCHAR(16) NOT NULL COMMENT 'SLIP (the sliding velocity) or ROLLING (the wheel rolling direction)',"
                      " bounce DOUBLE NOT NULL COMMENT 'restitution 0..1',"
                      " bounceVelocity DOUBLE NOT NULL COMMENT '[m/s] least impact speed that bounces',"
                      " softERP DOUBLE NULL COMMENT 'per step; NULL when stiffness is given',"
                      " softCFM DOUBLE NULL COMMENT 'per step; NULL when stiffness is given',"
                      " stiffness DOUBLE NULL COMMENT '[N/m] of the whole contact; NULL = softness per step',"
                      " damping DOUBLE NULL COMMENT '[N s/m] of the whole contact; NULL = softness per step',"
                      " rollingFriction DOUBLE NOT NULL COMMENT '[m] rolling resistance length',"
                      " PRIMARY KEY (materialID),"
                      " UNIQUE KEY bus (simulationID, busIndex),"
                      " KEY name (simulationID, name)"
                      ")") + kTableOptions,
          std::string("ALTER TABLE Body ADD COLUMN IF NOT EXISTS materialID INT UNSIGNED NULL"
                      " COMMENT 'the Material row of Body.material; NULL = the default material'"
                      " AFTER material"),
      }});
  m.push_back(Migration{
      5,
      "JointPose.continuousAngle, continuousAngle2, continuousAngle3: the joint angle without "
      "the wrap at +-pi, as the sim tracks it every step (NULL in rows logged before)",
      {
          // New columns at the end, NULL for old rows: MariaDB adds them
          // without rebuilding a large JointPose, and angle keeps its meaning.
          std::string("ALTER TABLE JointPose"
                      " ADD COLUMN IF NOT EXISTS continuousAngle DOUBLE NULL"
                      " COMMENT '[rad] or [m], axis 1: angle with rotations unwrapped (no jump at +-pi); NULL = logged before the sim published it',"
                      " ADD COLUMN IF NOT EXISTS continuousAngle2 DOUBLE NULL COMMENT 'axis 2 (0 if none)',"
                      " ADD COLUMN IF NOT EXISTS continuousAngle3 DOUBLE NULL COMMENT 'axis 3 (0 if none)'"),
      }});
  m.push_back(Migration{
      6,
      "Command.meantForBusSimulationID: the simulation a command was meant for "
      "(command_t.simulation_id, 0 = any; NULL in rows logged before)",
      {
          std::string("ALTER TABLE Command ADD COLUMN IF NOT EXISTS meantForBusSimulationID BIGINT NULL"
                      " COMMENT 'command_t.simulation_id: the Simulation.busSimulationID the sender meant it for; 0 = any; NULL = logged before the logger stored it'"
                      " AFTER simulationID"),
      }});
  m.push_back(Migration{
      7,
      "Simulation.tag: what the logger was told to mark its simulations with (simpartner-batch: "
      "the batch, the run and its values)",
      {
          std::string("ALTER TABLE Simulation ADD COLUMN IF NOT EXISTS tag VARCHAR(1024) NULL"
                      " COMMENT 'simpartner-logger --tag: e.g. batch=sweep run=3 contactMu=0.5; "
                      "NULL = none'"),
      }});
  m.push_back(Migration{
      8,
      "Simulation.engine: the physics engine the simulation ran on, ode or mujoco "
      "('ode' in rows logged before: every sim before it ran ODE)",
      {
          // Every simulation logged before the sim could run MuJoCo ran ODE.
          std::string("ALTER TABLE Simulation ADD COLUMN IF NOT EXISTS engine VARCHAR(32) NOT NULL"
                      " DEFAULT 'ode' COMMENT 'model_t.engine: ode or mujoco'"
                      " AFTER worldName"),
      }});
  m.push_back(Migration{
      9,
      "Material.soil and its figures: the soil of a ground of soft soil (docs/soil.md), "
      "NULL for other materials and in rows logged before",
      {
          std::string(
              "ALTER TABLE Material"
              " ADD COLUMN IF NOT EXISTS soil VARCHAR(255) NULL COMMENT 'material_t.soil_name: the soil library entry, or the material name when written out; NULL = not a soil',"
              " ADD COLUMN IF NOT EXISTS soilN DOUBLE NULL COMMENT 'sinkage exponent [-]',"
              " ADD COLUMN IF NOT EXISTS soilKc DOUBLE NULL COMMENT 'cohesive modulus of deformation [kN/m^(n+1)]',"
              " ADD COLUMN IF NOT EXISTS soilKphi DOUBLE NULL COMMENT 'frictional modulus of deformation [kN/m^(n+2)]',"
              " ADD COLUMN IF NOT EXISTS soilCohesion DOUBLE NULL COMMENT 'c [kPa]',"
              " ADD COLUMN IF NOT EXISTS soilFrictionAngle DOUBLE NULL COMMENT 'phi [deg]',"
              " ADD COLUMN IF NOT EXISTS soilShearModulus DOUBLE NULL COMMENT 'K, shear deformation modulus [m]',"
              " ADD COLUMN IF NOT EXISTS soilUnloadingStiffness DOUBLE NULL COMMENT '[kPa/m]',"
              " ADD COLUMN IF NOT EXISTS soilViscosity DOUBLE NULL COMMENT '[kPa s/m]'"),
      }});
  m.push_back(Migration{
      10,
      "WheelSoil: each wheel's sinkage, slip and soil force in the steps it pressed soft soil "
      "(state_t.wheel_soil, docs/soil.md)",
      {
          std::string("CREATE TABLE IF NOT EXISTS WheelSoil ("
                      " simulationRowID BIGINT UNSIGNED NOT NULL,"
                      " bodyID INT UNSIGNED NOT NULL COMMENT 'the wheel',"
                      " sinkage DOUBLE NOT NULL COMMENT '[m] lowest rim point below the untouched surface',"
                      " slip DOUBLE NOT NULL COMMENT '[-] 1 - v/(r omega) driving, r omega/v - 1 braking',"
                      " thrust DOUBLE NOT NULL COMMENT '[N] shear force along the rolling direction (traction H)',"
                      " drawbarPull DOUBLE NOT NULL COMMENT '[N] whole soil force along the rolling direction (H - compaction resistance)',"
                      " wheelLoad DOUBLE NOT NULL COMMENT '[N] whole soil force along the surface normal',"
                      " axleTorque DOUBLE NOT NULL COMMENT '[N m] of the shear about the axle, positive against a forward spin',"
                      " Fn_x DOUBLE NOT NULL COMMENT '[N] of the normal stresses, world frame',"
                      " Fn_y DOUBLE NOT NULL,"
                      " Fn_z DOUBLE NOT NULL,"
                      " Fs_x DOUBLE NOT NULL COMMENT '[N] of the shear stresses, world frame',"
                      " Fs_y DOUBLE NOT NULL,"
                      " Fs_z DOUBLE NOT NULL,"
                      " stuck BOOLEAN NOT NULL COMMENT 'sunk to the axle or deeper',"
                      " PRIMARY KEY (simulationRowID, bodyID)"
                      ")") + kTableOptions,
      }});
  m.push_back(Migration{
      11,
      "a view per sensor kind (ImuReading, GnssReading, EncoderReading, ...) with the readings' "
      "values in named columns",
      ReadingViews()});
  return m;
}

// "CREATE TABLE Pose", "ALTER TABLE LogGap": what a migration statement
// does, for messages.
std::string StatementName(const std::string& statement) {
  std::string words;
  int count = 0;
  size_t i = 0;
  while (i < statement.size() && count < 3) {
    const size_t end = statement.find(' ', i);
    std::string word = statement.substr(i, end == std::string::npos ? std::string::npos : end - i);
    i = end == std::string::npos ? statement.size() : end + 1;
    if (word == "IF" || word == "NOT" || word == "EXISTS" || word.empty()) continue;
    if (!words.empty()) words += " ";
    words += word;
    ++count;
  }
  return words;
}

}  // namespace

const std::vector<Migration>& Migrations() {
  static const std::vector<Migration> migrations = BuildMigrations();
  return migrations;
}

int LatestSchemaVersion() { return Migrations().back().version; }

int MigrateSchema(DbConnection* db, const std::function<void(const std::string&)>& notice) {
  db->UseDatabase(true);
  const std::string lock_name = Quoted("simpartner_schema." + db->target().database);
  if (db->QueryInt("SELECT GET_LOCK(" + lock_name + ", 60)", "GET_LOCK (schema migration)", 0) != 1)
    throw DbError(DbErrorKind::kOther, db->target().Server(), "GET_LOCK (schema migration)",
                  "another program held the schema lock for 60 s", 0, "");
  struct Unlock {
    DbConnection* db;
    std::string name;
    ~Unlock() {
      try {
        db->Execute("DO RELEASE_LOCK(" + name + ")", "RELEASE_LOCK");
      } catch (const DbError&) {
        // The lock goes with the connection.
      }
    }
  } unlock{db, lock_name};

  db->Execute("CREATE TABLE IF NOT EXISTS SchemaVersion ("
              " version INT NOT NULL PRIMARY KEY,"
              " description VARCHAR(1024) NOT NULL,"
              " appliedAt DATETIME(6) NOT NULL COMMENT 'UTC'"
              ")" + std::string(kTableOptions),
              "CREATE TABLE SchemaVersion");
  const int before = static_cast<int>(
      db->QueryInt("SELECT MAX(version) FROM SchemaVersion", "SELECT FROM SchemaVersion", 0));
  if (before > LatestSchemaVersion())
    throw DbError(DbErrorKind::kOther, db->target().Server(), "schema check",
                  "database '" + db->target().database + "' has schema version " +
                      std::to_string(before) + ", newer than this program's " +
                      std::to_string(LatestSchemaVersion()) + "; use a newer simpartner-logger",
                  0, "");
  for (const Migration& migration : Migrations()) {
    if (migration.version <= before) continue;
    for (const std::string& statement : migration.statements)
      db->Execute(statement, "migration " + std::to_string(migration.version) + ": " +
                                 StatementName(statement));
    db->Execute("INSERT INTO SchemaVersion (version, description, appliedAt) VALUES (" +
                    std::to_string(migration.version) + ", " + Quoted(migration.description) +
                    ", UTC_TIMESTAMP(6))",
                "INSERT INTO SchemaVersion");
    if (notice)
      notice("database '" + db->target().database + "': applied schema migration " +
             std::to_string(migration.version) + " (" + migration.description + ")");
  }
  return before;
}

}  // namespace simpartner::logger
