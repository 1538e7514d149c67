// The writer and the schema against a real MariaDB server (a private one per
// test): migrations, every step exactly once however often it is written,
// gaps, the simulation's life, the rights of the logger's user, the
// original's mixed-case queries, a server that refuses writes or goes away,
// and the query tool's CSV.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "logger_test_support.h"
#include "simpartner/command_t.hpp"
#include "simpartner/logger/axis_angle.h"
#include "simpartner/logger/query.h"
#include "simpartner/logger/schema.h"
#include "simpartner/logger/writer.h"

namespace simpartner::logger {
namespace {

using testing::ArmRun;
using testing::Gen3Run;
using testing::SimRun;

// simpartner-query list: its header line, then each simulation's line split
// at blanks (a time has one inside, an end time '-' none).
struct Listing {
  std::string text, header;
  std::vector<std::vector<std::string>> rows;
};
Listing List(DbConnection* db) {
  std::ostringstream out;
  ListSimulations(db, out);
  Listing listing{out.str(), "", {}};
  std::stringstream lines(listing.text);
  std::getline(lines, listing.header);
  for (std::string line; std::getline(lines, line);) {
    std::stringstream row(line);
    listing.rows.emplace_back();
    for (std::string f; row >> f;) listing.rows.back().push_back(f);
  }
  return listing;
}

// A ground of Wong's dry sand, written out (docs/soil.md).
constexpr const char* kSandGround =
    "<surface material=\"sand\"><a>0</a><b>1</b><c>0</c><d>0</d>"
    "</surface><material name=\"sand\"><mu>0.6</mu><soil><n>1.1</n><kc>0.99</kc>"
    "<kphi>1528.43</kphi><cohesion>1.04</cohesion><frictionAngle>28</frictionAngle>"
    "<shearModulus>0.025</shearModulus><unloadingStiffness>10000</unloadingStiffness>"
    "<viscosity>0</viscosity></soil></material>";

class DbTest : public testing::ServerTest {
 protected:
  std::unique_ptr<DbWriter> Writer(const std::string& database = "simpartner",
                                   InsertMethod method = InsertMethod::kMultiRowInsert) {
    WriterOptions options;
    options.method = method;
    options.lcm_url = "udpm://test";
    options.scratch_dir = dir_.string();
    return std::make_unique<DbWriter>(server_->LoggerTarget(database), options,
                                      [this](const std::string& s) { notices_.push_back(s); });
  }
  // Rows per step and per body of one simulation, each of which must be
  // `bodies` and `steps` respectively.
  void ExpectEveryStepOnce(const std::string& db, int64_t simulation, int64_t first, int64_t last,
                           int64_t bodies, int64_t joints) {
    const std::string sim = std::to_string(simulation);
    const int64_t steps = last - first + 1;
    EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM SimulationRow WHERE simulationID = " + sim, db), steps);
    EXPECT_EQ(QueryInt("SELECT COUNT(DISTINCT step) FROM SimulationRow WHERE simulationID = " + sim +
                           " AND step BETWEEN " + std::to_string(first) + " AND " + std::to_string(last),
                       db),
              steps);
    for (const char* table : {"Pose", "ForceAndTorque"}) {
      EXPECT_EQ(QueryInt(std::string("SELECT COUNT(*) FROM (SELECT r.step FROM SimulationRow r JOIN ") +
                             table + " t USING (simulationRowID) WHERE r.simulationID = " + sim +
                             " GROUP BY r.step HAVING COUNT(*) <> " + std::to_string(bodies) + ") x",
                         db),
                0) << table << ": a step without exactly one row per body";
      EXPECT_EQ(QueryInt(std::string("SELECT COUNT(*) FROM (SELECT t.bodyID FROM SimulationRow r JOIN ") +
                             table + " t USING (simulationRowID) WHERE r.simulationID = " + sim +
                             " GROUP BY t.bodyID HAVING COUNT(*) <> " + std::to_string(steps) + ") x",
                         db),
                0) << table << ": a body without exactly one row per step";
      EXPECT_EQ(QueryInt(std::string("SELECT COUNT(*) FROM SimulationRow r JOIN ") + table +
                             " t USING (simulationRowID) WHERE r.simulationID = " + sim,
                         db),
                steps * bodies) << table;
    }
    EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM SimulationRow r JOIN JointPose t USING (simulationRowID) "
                       "WHERE r.simulationID = " + sim,
                       db),
              steps * joints);
  }
  // world_xml run `steps` steps as simulation `simulation_id`: its model
  // and every state written.
  SimRun WriteRun(const std::string& world_xml, int64_t simulation_id, int steps) {
    auto sim = sim::testing::MakeSim(world_xml);
    sim->Reset(simulation_id);
    const SimRun run = testing::MakeRun(sim.get(), steps);
    WriteAll(run);
    return run;
  }
  // The run's model and every state, in one batch.
  void WriteAll(const SimRun& run) {
    std::vector<Record> records = {run.ModelRecord()};
    for (Record& r : run.StateRecords(1, static_cast<int64_t>(run.states.size())))
      records.push_back(std::move(r));
    Writer()->Write(records);
  }
  // The reader's session (SELECT only), in the logger's database.
  std::unique_ptr<DbConnection> Reader() {
    DbTarget target = server_->LoggerTarget("simpartner");
    target.option_file = server_->reader_options();
    auto db = DbConnection::Open(target, false);
    db->UseDatabase(false);
    return db;
  }
  std::vector<std::string> notices_;
};

TEST_F(DbTest, MigrationsCreateTheSchemaAndUpgradeOlderOnes) {
  auto db = DbConnection::Open(server_->LoggerTarget("simpartner_a"), false);
  EXPECT_EQ(MigrateSchema(db.get(), nullptr), 0);
  EXPECT_EQ(QueryInt("SELECT MAX(version) FROM SchemaVersion", "simpartner_a"), LatestSchemaVersion());
  EXPECT_EQ(MigrateSchema(db.get(), nullptr), LatestSchemaVersion());  // nothing left to do
  for (const char* table : {"Simulation", "Robot", "RobotComponent", "Body", "Joint", "Sensor",
                            "Actuator", "SimulationRow", "Pose", "JointPose", "ForceAndTorque",
                            "LogGap", "SensorReading", "Command", "CommandReply", "Material",
                            "WheelSoil"}) {
    EXPECT_EQ(QueryInt(std::string("SELECT COUNT(*) FROM information_schema.TABLES WHERE "
                                   "TABLE_SCHEMA = 'simpartner_a' AND TABLE_NAME = '") + table + "'",
                       "simpartner_a"),
              1) << table;
  }

  // A database the first version of the logger made.
  auto old = Admin("simpartner_b");
  old->Execute("CREATE TABLE SchemaVersion (version INT NOT NULL PRIMARY KEY, description "
               "VARCHAR(1024) NOT NULL, appliedAt DATETIME(6) NOT NULL)", "");
  for (const std::string& statement : Migrations().at(0).statements) old->Execute(statement, "");
  old->Execute("INSERT INTO SchemaVersion VALUES (1, 'v1', NOW())", "");
  old->Execute("INSERT INTO LogGap VALUES (1, 11, 14, 4, NOW())", "");  // a gap of that logger
  // A simulation of that logger (ODE then was the only engine).
  old->Execute("INSERT INTO Simulation (busSimulationID, host, lcmUrl, startTime, worldFile, "
               "worldName, parameters, stepSize, stateEvery, logInterval, gravityX, gravityY, "
               "gravityZ) VALUES (5, 'old', 'udpm://', NOW(), 'w.xml', 'W', '', 0.001, 1, 1, 0, "
               "-9.81, 0)", "");
  for (const std::string& statement : Migrations().at(1).statements) old->Execute(statement, "");
  old->Execute("INSERT INTO SchemaVersion VALUES (2, 'v2', NOW())", "");
  old->Execute("INSERT INTO Command (simulationID, receivedUtime, sentUtime, sender, requestID, robot, "
               "target, port, action, applyAtStep, vals, text) VALUES (1, 5, 4, 'teleop', 1, '', "
               "'Spin', 0, 'SET', -1, '1', '')", "");  // a command of that logger
  // The query tool lists a database no logger has migrated yet: its
  // simulations ran on ODE.
  const Listing unmigrated = List(old.get());
  ASSERT_EQ(unmigrated.rows.size(), 1u) << unmigrated.text;
  ASSERT_EQ(unmigrated.rows[0].size(), 12u) << unmigrated.text;
  EXPECT_EQ(unmigrated.rows[0][4], "ode") << unmigrated.text;
  std::vector<std::string> notices;
  auto b = DbConnection::Open(server_->LoggerTarget("simpartner_b"), false);
  EXPECT_EQ(MigrateSchema(b.get(), [&](const std::string& s) { notices.push_back(s); }), 2);
  EXPECT_EQ(QueryInt("SELECT MAX(version) FROM SchemaVersion", "simpartner_b"), 11);
  ASSERT_EQ(notices.size(), 9u);
  EXPECT_NE(notices[0].find("applied schema migration 3 (LogGap.reason"), std::string::npos);
  EXPECT_NE(notices[1].find("applied schema migration 4 (Material"), std::string::npos);
  EXPECT_NE(notices[2].find("applied schema migration 5 (JointPose.continuousAngle"), std::string::npos);
  EXPECT_NE(notices[3].find("applied schema migration 6 (Command.meantForBusSimulationID"), std::string::npos);
  EXPECT_NE(notices[4].find("applied schema migration 7 (Simulation.tag"), std::string::npos);
  EXPECT_NE(notices[5].find("applied schema migration 8 (Simulation.engine"), std::string::npos);
  EXPECT_NE(notices[6].find("applied schema migration 9 (Material.soil"), std::string::npos);
  EXPECT_NE(notices[7].find("applied schema migration 10 (WheelSoil"), std::string::npos);
  EXPECT_NE(notices[8].find("applied schema migration 11 (a view per sensor kind"),
            std::string::npos);
  // Simulations logged before migration 8 ran on ODE, the only engine then.
  EXPECT_EQ(QueryRows(old.get(), "SELECT busSimulationID, engine FROM Simulation"),
            (std::vector<std::string>{"5\tode"}));
  // Simulations logged before migration 7 carry no tag: NULL.
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM information_schema.COLUMNS WHERE TABLE_SCHEMA = "
                     "'simpartner_b' AND TABLE_NAME = 'Simulation' AND COLUMN_NAME = 'tag' AND "
                     "IS_NULLABLE = 'YES'",
                     "simpartner_b"),
            1);
  // Commands logged before migration 6: whom they were meant for is unknown.
  EXPECT_EQ(QueryRows(old.get(), "SELECT sender, meantForBusSimulationID IS NULL FROM Command"),
            (std::vector<std::string>{"teleop\t1"}));
  // Joint rows logged before migration 5 have no continuous angle: NULL.
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM information_schema.COLUMNS WHERE TABLE_SCHEMA = "
                     "'simpartner_b' AND TABLE_NAME = 'JointPose' AND COLUMN_NAME LIKE "
                     "'continuousAngle%' AND IS_NULLABLE = 'YES'",
                     "simpartner_b"),
            3);
  // Bodies logged before migration 4 keep their material name; their
  // Material row is unknown.
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM information_schema.COLUMNS WHERE TABLE_SCHEMA = "
                     "'simpartner_b' AND TABLE_NAME = 'Body' AND COLUMN_NAME = 'materialID' AND "
                     "IS_NULLABLE = 'YES'",
                     "simpartner_b"),
            1);
  // The old gap got the reason old gaps had: never received.
  EXPECT_EQ(QueryRows(old.get(), "SELECT firstStep, missing, reason FROM LogGap"),
            (std::vector<std::string>{"11\t4\tnever received (lost on the bus, or sent while no logger ran)"}));
  // Migrations cut short after adding their columns run again harmlessly.
  old->Execute("DELETE FROM SchemaVersion WHERE version >= 3", "");
  EXPECT_EQ(MigrateSchema(b.get(), nullptr), 2);
  EXPECT_EQ(QueryInt("SELECT MAX(version) FROM SchemaVersion", "simpartner_b"), 11);

  // A database from a newer logger is left alone.
  old->Execute("INSERT INTO SchemaVersion VALUES (99, 'from the future', NOW())", "");
  try {
    MigrateSchema(b.get(), nullptr);
    FAIL() << "a newer schema was accepted";
  } catch (const DbError& e) {
    EXPECT_NE(std::string(e.what()).find("database 'simpartner_b' has schema version 99, newer than "
                                         "this program's 11"),
              std::string::npos) << e.what();
  }
}

TEST_F(DbTest, EveryStepOnceHoweverOftenItIsWritten) {
  const SimRun run = ArmRun(300, 41);
  {
    auto writer = Writer();
    writer->Write({run.ModelRecord()});
    // Batches of uneven size, then all of them again (a replayed spool).
    const std::vector<Record> states = run.StateRecords(1, 300);
    for (size_t i = 0; i < states.size(); i += 37)
      writer->Write(std::vector<Record>(states.begin() + static_cast<std::ptrdiff_t>(i),
                                        states.begin() + static_cast<std::ptrdiff_t>(std::min(states.size(), i + 37))));
    const WriteResult again = writer->Write(states);
    EXPECT_EQ(again.states_written, 0u);
    EXPECT_EQ(again.states_present, 300u);
  }
  // A new writer (a restarted logger) gets the model and old states again.
  auto writer = Writer();
  std::vector<Record> replay = {run.ModelRecord()};
  for (Record& r : run.StateRecords(250, 300)) replay.push_back(std::move(r));
  const WriteResult result = writer->Write(replay);
  EXPECT_EQ(result.states_written, 0u);
  EXPECT_EQ(result.states_present, 51u);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Simulation"), 1);
  ExpectEveryStepOnce("simpartner", 1, 1, 300, 3, 2);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM LogGap"), 0);
  EXPECT_NE(notices_.back().find("resuming simulation 1 (bus simulation id 41"), std::string::npos)
      << notices_.back();
}

TEST_F(DbTest, RowsHoldTheStateInSiUnitsAndAxisAngle) {
  const SimRun run = ArmRun(1500, 7);
  WriteAll(run);
  auto db = Admin();
  for (int64_t step : {1, 700, 1500}) {
    const state_t& s = run.states[static_cast<size_t>(step - 1)];
    ASSERT_EQ(s.step, step);
    const body_state_t& arm = s.bodies[1];
    // Axis-angle straight from the quaternion, another way than the writer's.
    const double* q = arm.orientation;
    const double sign = q[0] < 0 ? -1.0 : 1.0;
    const double vector_norm = std::sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double angle = 2 * std::atan2(vector_norm, std::abs(q[0]));
    const std::vector<std::string> rows = QueryRows(
        db.get(), "SELECT r.simulationTime, p.x, p.y, p.z, p.axisX, p.axisY, p.axisZ, p.angle, "
                  "f.F_y FROM SimulationRow r JOIN Pose p USING (simulationRowID) JOIN "
                  "ForceAndTorque f ON f.simulationRowID = r.simulationRowID AND f.bodyID = "
                  "p.bodyID JOIN Body b ON b.bodyID = p.bodyID WHERE b.name = 'Arm' AND r.step = " +
                      std::to_string(step));
    ASSERT_EQ(rows.size(), 1u);
    std::vector<double> v;
    std::stringstream fields(rows[0]);
    std::string field;
    while (std::getline(fields, field, '\t')) v.push_back(std::stod(field));
    EXPECT_DOUBLE_EQ(v[0], step * 0.001);
    EXPECT_EQ(v[1], arm.position[0]);  // exact: shortest round-trip text
    EXPECT_EQ(v[2], arm.position[1]);
    EXPECT_EQ(v[3], arm.position[2]);
    EXPECT_NEAR(v[7], angle, 1e-12);
    if (angle > 1e-6) {
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(v[4 + k], sign * q[k + 1] / vector_norm, 1e-9);
    }
    EXPECT_EQ(v[8], arm.contact_force[1]);
  }
  // The arm swung up towards 3 rad about z: the logged angle went past 2.5.
  EXPECT_GT(QueryInt("SELECT COUNT(*) FROM Pose p JOIN Body b USING (bodyID) WHERE b.name = 'Arm' "
                     "AND p.angle > 2.5 AND ABS(p.axisZ) > 0.999"),
            100);
  const std::vector<std::string> joint = QueryRows(
      db.get(), "SELECT j.type, j.numAxes, j.loStop1, b1.name, b2.name FROM `Joint` j JOIN Body b1 "
                "ON b1.bodyID = j.body1ID JOIN Body b2 ON b2.bodyID = j.body2ID WHERE j.name = 'Shoulder'");
  EXPECT_EQ(joint, (std::vector<std::string>{"HINGE\t1\tNULL\tBase\tArm"}));
  EXPECT_EQ(QueryRows(db.get(), "SELECT type, name FROM RobotComponent ORDER BY type, name"),
            (std::vector<std::string>{"BODY\tArm", "BODY\tBase", "BODY\tWheel", "JOINT\tAxle",
                                      "JOINT\tShoulder", "SENSOR\tArmPosition", "SENSOR\tEcho",
                                      "SENSOR\tShoulderLoad", "ACTUATOR\tArmMotor", "ACTUATOR\tSpin"}));
}

// A world with a rolling tyre of physical softness and an isotropic ice of
// per-step softness: the Material rows say what the files say, and each
// body points at its material's row.
TEST_F(DbTest, MaterialsAreStoredWithTheirBodies) {
  const std::string world =
      "<world name=\"Materials\"><surface material=\"ice\"><a>0</a><b>1</b><c>0</c><d>0</d>"
      "</surface>"
      "<material name=\"tyre\"><mu>0.8</mu><mu2>0.4</mu2>"
      "<frictionDirection>rolling</frictionDirection><bounce>0.1</bounce>"
      "<stiffness>200000</stiffness><damping>7000</damping>"
      "<rollingFriction>0.002</rollingFriction></material>"
      "<material name=\"ice\"><mu>0.025</mu><softERP>0.3</softERP><softCFM>0.0002</softCFM>"
      "</material>"
      "<object type=\"Cylinder\" name=\"Wheel\" material=\"tyre\"><mass>5</mass>"
      "<radius>0.3</radius><length>0.2</length>" + sim::testing::Transform(0, 0.3, 0) +
      "</object>"
      "<object type=\"Box\" name=\"Crate\"><mass>1</mass>" +
      sim::testing::Vec("size", 0.5, 0.5, 0.5) + sim::testing::Transform(2, 0.25, 0) +
      "</object></world>";
  WriteRun(world, 77, 3);
  auto db = Admin();
  EXPECT_EQ(QueryRows(db.get(), "SELECT name, mu, mu2, frictionDirection, bounce, bounceVelocity, "
                                "softERP, softCFM, stiffness, damping, rollingFriction FROM Material "
                                "ORDER BY name"),
            (std::vector<std::string>{
                "ice\t0.025\t0.025\tSLIP\t0\t0.1\t0.3\t0.0002\tNULL\tNULL\t0",
                "tyre\t0.8\t0.4\tROLLING\t0.1\t0.1\tNULL\tNULL\t200000\t7000\t0.002"}));
  EXPECT_EQ(QueryRows(db.get(), "SELECT b.name, b.material, m.name FROM Body b LEFT JOIN Material m "
                                "USING (materialID) ORDER BY b.name"),
            (std::vector<std::string>{"Crate\t\tNULL", "Wheel\ttyre\ttyre"}));
}

// A ground of soil (docs/soil.md): its Material row carries the soil's
// name and figures; a material that is no soil has NULL there.
TEST_F(DbTest, ASoilIsStoredWithItsMaterial) {
  const std::string world = std::string("<world name=\"Soil\">") + kSandGround +
                            "<material name=\"ice\"><mu>0.025</mu></material></world>";
  auto sim = sim::testing::MakeSim(world);
  sim->Reset(78);
  const SimRun run = testing::MakeRun(sim.get(), 1);
  auto writer = Writer();
  writer->Write({run.ModelRecord()});
  auto db = Admin();
  EXPECT_EQ(QueryRows(db.get(), "SELECT name, soil, soilN, soilKc, soilKphi, soilCohesion, "
                                "soilFrictionAngle, soilShearModulus, soilUnloadingStiffness, "
                                "soilViscosity FROM Material ORDER BY name"),
            (std::vector<std::string>{
                "ice\tNULL\tNULL\tNULL\tNULL\tNULL\tNULL\tNULL\tNULL\tNULL",
                "sand\tsand\t1.1\t0.99\t1528.43\t1.04\t28\t0.025\t10000\t0"}));
}

// Simulation.engine is what SIM_MODEL names; a model with no engine comes
// from a sender older than the field, and every such sim ran ODE.
TEST_F(DbTest, EachSimulationKeepsTheEngineItsModelNames) {
  SimRun mujoco = ArmRun(5, 300);
  mujoco.model.engine = "mujoco";
  SimRun older = ArmRun(5, 400);
  older.model.engine = "";
  auto writer = Writer();
  std::vector<Record> records = {mujoco.ModelRecord()};
  for (Record& r : mujoco.StateRecords(1, 5)) records.push_back(std::move(r));
  records.push_back(older.ModelRecord());
  for (Record& r : older.StateRecords(1, 5)) records.push_back(std::move(r));
  writer->Write(records);
  auto db = Admin();
  EXPECT_EQ(QueryRows(db.get(), "SELECT busSimulationID, engine FROM Simulation ORDER BY simulationID"),
            (std::vector<std::string>{"300\tmujoco", "400\tode"}));
  EXPECT_EQ(SimulationEngine(db.get(), 1), "mujoco");
  LoggedRunRequest request;
  request.simulation = "1";
  EXPECT_EQ(ReadLoggedRun(db.get(), request).engine, "mujoco");
  // simpartner-query list: the engine after the world.
  const Listing listing = List(db.get());
  EXPECT_NE(listing.header.find(" world                engine  start (UTC)"), std::string::npos)
      << listing.header;
  ASSERT_EQ(listing.rows.size(), 2u) << listing.text;
  for (const auto& row : listing.rows) ASSERT_GE(row.size(), 5u) << listing.text;
  EXPECT_EQ(listing.rows[0][4], "mujoco") << listing.text;
  EXPECT_EQ(listing.rows[1][4], "ode") << listing.text;
}

TEST_F(DbTest, GapsAreRecordedAlsoAcrossARestart) {
  const SimRun run = ArmRun(40, 5);
  {
    auto writer = Writer();
    std::vector<Record> records = {run.ModelRecord()};
    for (Record& r : run.StateRecords(1, 10)) records.push_back(std::move(r));
    for (Record& r : run.StateRecords(15, 20)) records.push_back(std::move(r));
    writer->Write(records);
  }
  auto writer = Writer();  // restarted: knows the last step only from the database
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(30, 31)) records.push_back(std::move(r));
  writer->Write(records);
  auto db = Admin();
  EXPECT_EQ(QueryRows(db.get(), "SELECT firstStep, lastStep, missing FROM LogGap ORDER BY firstStep"),
            (std::vector<std::string>{"11\t14\t4", "21\t29\t9"}));
}

TEST_F(DbTest, ARestartedSimIsANewSimulationAndTheOldOneIsClosed) {
  const SimRun first = ArmRun(20, 100);
  const SimRun second = ArmRun(20, 200);
  auto writer = Writer();
  std::vector<Record> records = {first.ModelRecord()};
  for (Record& r : first.StateRecords(1, 20)) records.push_back(std::move(r));
  sensor_reading_t reading{};
  reading.simulation_id = 100;
  reading.sensor = 0;
  reading.step = 20;
  reading.values = {1.5, -2.25};
  reading.num_values = 2;
  records.push_back(testing::MakeRecord(RecordKind::kSensor, 100, reading, 555));
  command_t command = sim::testing::Command("Spin", command_t::ACTION_SET, {10, 0.5});
  command.text = "it's a \"test\"";
  command.simulation_id = 100;
  records.push_back(testing::MakeRecord(RecordKind::kCommand, 100, command, 556));
  records.push_back(second.ModelRecord());
  for (Record& r : second.StateRecords(1, 5)) records.push_back(std::move(r));
  records.push_back(MakeEndedRecord(200, 0, EndedPayload{5, EndKind::kStopped, ""}));
  writer->Write(records);
  writer->Write(records);  // again: nothing new
  auto db = Admin();
  EXPECT_EQ(QueryRows(db.get(), "SELECT simulationID, busSimulationID, endTime IS NOT NULL, endReason, "
                                "lastStep FROM Simulation ORDER BY simulationID"),
            (std::vector<std::string>{
                "1\t100\t1\ta new simulation started on the bus (the sim restarted or was reset)\t20",
                "2\t200\t1\tthe sim stopped\t5"}));
  ExpectEveryStepOnce("simpartner", 1, 1, 20, 3, 2);
  ExpectEveryStepOnce("simpartner", 2, 1, 5, 3, 2);
  EXPECT_EQ(QueryRows(db.get(), "SELECT s.name, r.step, r.vals FROM SensorReading r JOIN Sensor s USING (sensorID)"),
            (std::vector<std::string>{"ArmPosition\t20\t1.5,-2.25"}));
  EXPECT_EQ(QueryRows(db.get(), "SELECT simulationID, meantForBusSimulationID, target, action, vals, text FROM Command"),
            (std::vector<std::string>{"1\t100\tSpin\tSET\t10,0.5\tit's a \"test\""}));
}

TEST_F(DbTest, LoadDataWritesTheSameRowsAsInsert) {
  const SimRun run = ArmRun(200, 3);
  for (auto [db, method] : {std::pair{"simpartner_i", InsertMethod::kMultiRowInsert},
                            std::pair{"simpartner_l", InsertMethod::kLoadDataLocal}}) {
    auto writer = Writer(db, method);
    std::vector<Record> records = {run.ModelRecord()};
    for (Record& r : run.StateRecords(1, 200)) records.push_back(std::move(r));
    writer->Write(records);
    writer->Write(records);
    ExpectEveryStepOnce(db, 1, 1, 200, 3, 2);
  }
  const std::string dump =
      "SELECT r.step, p.bodyID, p.x, p.y, p.z, p.axisX, p.axisY, p.axisZ, p.angle, f.F_x, f.T_z, "
      "j.angle, j.rate, j.F_y FROM SimulationRow r JOIN Pose p USING (simulationRowID) JOIN "
      "ForceAndTorque f ON f.simulationRowID = r.simulationRowID AND f.bodyID = p.bodyID JOIN "
      "JointPose j ON j.simulationRowID = r.simulationRowID ORDER BY r.step, p.bodyID, j.jointID";
  auto a = Admin("simpartner_i");
  auto b = Admin("simpartner_l");
  const std::vector<std::string> rows = QueryRows(a.get(), dump);
  EXPECT_EQ(rows.size(), 200u * 3 * 2);
  EXPECT_EQ(rows, QueryRows(b.get(), dump));
}

TEST_F(DbTest, AutoUsesInsertWhenTheServerRefusesLoadData) {
  Admin()->Execute("SET GLOBAL local_infile = 0", "");
  const SimRun run = ArmRun(120, 3);
  auto writer = Writer("simpartner", InsertMethod::kAuto);
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(1, 120)) records.push_back(std::move(r));  // big enough for LOAD DATA
  writer->Write(records);
  ExpectEveryStepOnce("simpartner", 1, 1, 120, 3, 2);
  bool told = false;
  for (const std::string& n : notices_) told = told || n.find("refuses LOAD DATA LOCAL") != std::string::npos;
  EXPECT_TRUE(told);
  // Asked for explicitly, a refused LOAD DATA is an error naming the cause.
  auto strict = Writer("simpartner_s", InsertMethod::kLoadDataLocal);
  try {
    strict->Write(records);
    FAIL() << "LOAD DATA LOCAL went through with local_infile = 0";
  } catch (const DbError& e) {
    EXPECT_NE(std::string(e.what()).find("LOAD DATA LOCAL INTO Pose"), std::string::npos) << e.what();
  }
  // The batch failed after its SimulationRow rows were sent: none of them
  // was committed.
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM SimulationRow", "simpartner_s"), 0);
}

// The LOAD DATA scratch file cannot be written (its disk full, here its
// directory missing): the batch is rolled back, not committed without its
// Pose, ForceAndTorque and JointPose rows, and goes again as INSERTs.
TEST_F(DbTest, AnUnwritableScratchFileRollsTheBatchBackAndItGoesAsInserts) {
  const SimRun run = ArmRun(300, 3);
  WriterOptions options;
  options.method = InsertMethod::kLoadDataLocal;
  options.lcm_url = "udpm://test";
  options.scratch_dir = (dir_ / "no such directory").string();
  DbWriter writer(server_->LoggerTarget("simpartner"), options,
                  [this](const std::string& s) { notices_.push_back(s); });
  writer.Write({run.ModelRecord()});
  const std::vector<Record> states = run.StateRecords(1, 300);
  for (size_t i = 0; i < states.size(); i += 100) {
    const WriteResult result = writer.Write(std::vector<Record>(
        states.begin() + static_cast<std::ptrdiff_t>(i), states.begin() + static_cast<std::ptrdiff_t>(i + 100)));
    EXPECT_EQ(result.states_written, 100u);
  }
  ExpectEveryStepOnce("simpartner", 1, 1, 300, 3, 2);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM LogGap"), 0);
  size_t told = 0;
  for (const std::string& n : notices_)
    if (n.find("cannot write " + options.scratch_dir + "/loaddata-Pose.tsv") != std::string::npos &&
        n.find("rolled back and goes as multi-row INSERTs") != std::string::npos)
      ++told;
  EXPECT_EQ(told, 1u) << "told once, not for every batch";
}

// Scratch files go as soon as the server has read them.
TEST_F(DbTest, LoadDataLeavesNoScratchFiles) {
  const SimRun run = ArmRun(100, 3);
  auto writer = Writer("simpartner", InsertMethod::kLoadDataLocal);
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(1, 100)) records.push_back(std::move(r));
  writer->Write(records);
  ExpectEveryStepOnce("simpartner", 1, 1, 100, 3, 2);
  for (const auto& entry : std::filesystem::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().rfind("loaddata-", 0), std::string::npos) << entry.path();
}

// Steps whose SimulationRow is there without all of their rows (what the
// logger before this one committed when its scratch file failed) are not
// "already there": written again, they get their missing rows.
TEST_F(DbTest, AStepWithoutAllItsRowsIsCompletedNotSkipped) {
  const SimRun run = ArmRun(100, 8);
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(1, 100)) records.push_back(std::move(r));
  Writer()->Write(records);
  auto admin = Admin();
  admin->Execute("DELETE p FROM Pose p JOIN SimulationRow r USING (simulationRowID) WHERE r.step BETWEEN 40 AND 49", "");
  admin->Execute("DELETE f FROM ForceAndTorque f JOIN SimulationRow r USING (simulationRowID) WHERE r.step BETWEEN 45 AND 59", "");
  admin->Execute("DELETE j FROM JointPose j JOIN SimulationRow r USING (simulationRowID) WHERE r.step = 70 AND j.jointID = 1", "");
  const WriteResult result = Writer()->Write(records);
  EXPECT_EQ(result.states_repaired, 21u);  // 40..59 and 70
  EXPECT_EQ(result.states_present, 79u);
  ExpectEveryStepOnce("simpartner", 1, 1, 100, 3, 2);
}

// Steps the receiver could not keep (its spool disk full) arrive as gap
// records: LogGap holds them with the reason, steps that never came with
// theirs, and each missing step is counted once.
TEST_F(DbTest, GapRecordsGoIntoLogGapWithTheirReason) {
  const SimRun run = ArmRun(60, 5);
  auto writer = Writer();
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(1, 10)) records.push_back(std::move(r));
  records.push_back(MakeGapRecord(5, 0, GapPayload{11, 20, 10, "refused: spool disk full"}));
  for (Record& r : run.StateRecords(21, 30)) records.push_back(std::move(r));
  // 31..33 lost on the bus, then 34..40 refused.
  records.push_back(MakeGapRecord(5, 0, GapPayload{34, 40, 7, "refused again"}));
  for (Record& r : run.StateRecords(41, 45)) records.push_back(std::move(r));
  for (Record& r : run.StateRecords(48, 50)) records.push_back(std::move(r));  // 46, 47 lost
  writer->Write(records);
  // The gap record alone in a later batch, then the steps after it.
  writer->Write({MakeGapRecord(5, 0, GapPayload{51, 55, 5, "refused at last"})});
  writer->Write(run.StateRecords(56, 60));
  auto db = Admin();
  const std::string lost = "never received (lost on the bus, or sent while no logger ran)";
  EXPECT_EQ(QueryRows(db.get(), "SELECT firstStep, lastStep, missing, reason FROM LogGap ORDER BY firstStep"),
            (std::vector<std::string>{"11\t20\t10\trefused: spool disk full", "31\t33\t3\t" + lost,
                                      "34\t40\t7\trefused again", "46\t47\t2\t" + lost,
                                      "51\t55\t5\trefused at last"}));
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM SimulationRow") +
                QueryInt("SELECT SUM(missing) FROM LogGap"),
            60);
  // simpartner-query list counts them as missing.
  const Listing listing = List(db.get());
  ASSERT_EQ(listing.rows.size(), 1u) << listing.text;
  const std::vector<std::string>& fields = listing.rows[0];
  ASSERT_EQ(fields.size(), 12u) << listing.text;
  EXPECT_EQ(fields[8], "33") << listing.text;   // steps
  EXPECT_EQ(fields[10], "27") << listing.text;  // missing
}

// A simulation whose sim went silent is closed at the last step seen,
// with the reason.
TEST_F(DbTest, ASilentSimulationIsClosedWithItsReason) {
  const SimRun run = ArmRun(20, 5);
  auto writer = Writer();
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(1, 20)) records.push_back(std::move(r));
  records.push_back(MakeEndedRecord(5, 0, EndedPayload{20, EndKind::kSilent, "the sim went silent"}));
  records.push_back(MakeEndedRecord(5, 0, EndedPayload{20, EndKind::kStopped, ""}));  // closed already
  writer->Write(records);
  auto db = Admin();
  EXPECT_EQ(QueryRows(db.get(), "SELECT endTime IS NOT NULL, endReason, lastStep FROM Simulation"),
            (std::vector<std::string>{"1\tthe sim went silent\t20"}));
  size_t closed = 0;
  for (const std::string& n : notices_) closed += n.find("closed simulation 1") != std::string::npos;
  EXPECT_EQ(closed, 1u);
}

// A simulation closed as silent whose sim is heard again is open again
// (as a reader sees it), with the silence in LogGap, and closes normally
// at its end; writing it all again changes nothing.
TEST_F(DbTest, ASilentSimulationHeardAgainIsReopened) {
  const SimRun run = ArmRun(30, 5);
  auto writer = Writer();
  std::vector<Record> before = {run.ModelRecord()};
  for (Record& r : run.StateRecords(1, 20)) before.push_back(std::move(r));
  before.push_back(MakeEndedRecord(5, 0, EndedPayload{20, EndKind::kSilent, "the sim went silent"}));
  writer->Write(before);
  auto db = Admin();
  const std::string state = "SELECT endTime IS NOT NULL, endReason, lastStep FROM Simulation";
  EXPECT_EQ(QueryRows(db.get(), state), (std::vector<std::string>{"1\tthe sim went silent\t20"}));
  std::vector<Record> after = {MakeReopenedRecord(5, 0, "heard again after 4.0 s"),
                               MakeGapRecord(5, 0, GapPayload{20, 21, 0, "the sim was silent for 4.0 s"})};
  for (Record& r : run.StateRecords(21, 25)) after.push_back(std::move(r));
  writer->Write(after);
  EXPECT_EQ(QueryRows(db.get(), state), (std::vector<std::string>{"0\tNULL\tNULL"}));
  std::vector<Record> end = run.StateRecords(26, 30);
  end.push_back(MakeEndedRecord(5, 0, EndedPayload{30, EndKind::kStopped, ""}));
  writer->Write(end);
  const auto expect_final = [&] {
    EXPECT_EQ(QueryRows(db.get(), state), (std::vector<std::string>{"1\tthe sim stopped\t30"}));
    EXPECT_EQ(QueryRows(db.get(), "SELECT simulationID, firstStep, lastStep, missing, reason FROM LogGap"),
              (std::vector<std::string>{"1\t20\t21\t0\tthe sim was silent for 4.0 s"}));
    ExpectEveryStepOnce("simpartner", 1, 1, 30, 3, 2);
  };
  expect_final();
  size_t reopened = 0;
  for (const std::string& n : notices_)
    reopened += n == "reopened simulation 1: heard again after 4.0 s";
  EXPECT_EQ(reopened, 1u) << ::testing::PrintToString(notices_);
  // A replayed spool, in order: the same rows.
  for (const auto* records : {&before, &after, &end}) writer->Write(*records);
  expect_final();
}

// A logger started after another closed a simulation as silent: the
// sim's model coming again shows it alive, so it is open again.
TEST_F(DbTest, ASilentSimulationIsReopenedByTheNextLoggerWhenItsModelComes) {
  const SimRun run = ArmRun(30, 5);
  {
    auto writer = Writer();
    std::vector<Record> records = {run.ModelRecord()};
    for (Record& r : run.StateRecords(1, 20)) records.push_back(std::move(r));
    records.push_back(MakeEndedRecord(
        5, 0, EndedPayload{20, EndKind::kSilent, "the sim went silent: no SIM_STATE or SIM_STATUS for 10 s"}));
    writer->Write(records);
  }
  auto db = Admin();
  const std::string state = "SELECT endTime IS NOT NULL, lastStep FROM Simulation";
  EXPECT_EQ(QueryRows(db.get(), state), (std::vector<std::string>{"1\t20"}));
  auto next = Writer();
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(21, 30)) records.push_back(std::move(r));
  next->Write(records);
  EXPECT_EQ(QueryRows(db.get(), state), (std::vector<std::string>{"0\tNULL"}));
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Simulation"), 1);
  ExpectEveryStepOnce("simpartner", 1, 1, 30, 3, 2);
  // A simulation closed for another reason stays closed.
  next->Write({MakeEndedRecord(5, 0, EndedPayload{30, EndKind::kStopped, ""})});
  auto third = Writer();
  third->Write({run.ModelRecord()});
  EXPECT_EQ(QueryRows(db.get(), state), (std::vector<std::string>{"1\t30"}));
}

TEST_F(DbTest, TheLoggerUserHasOnlyTheRightsItNeeds) {
  auto writer = Writer();
  const SimRun run = ArmRun(3, 1);
  writer->Write({run.ModelRecord(), run.StateRecord(0)});
  auto logger = DbConnection::Open(server_->LoggerTarget("simpartner"), false);
  logger->UseDatabase(false);
  auto refused = [](DbConnection* db, const std::string& sql) {
    try {
      db->Execute(sql, sql);
    } catch (const DbError& e) {
      return e.code();
    }
    return 0;
  };
  EXPECT_EQ(refused(logger.get(), "DROP TABLE Pose"), 1142);
  EXPECT_EQ(refused(logger.get(), "DELETE FROM Pose"), 1142);
  EXPECT_EQ(refused(logger.get(), "CREATE DATABASE other"), 1044);
  EXPECT_EQ(refused(logger.get(), "SELECT * FROM mysql.user"), 1142);
  EXPECT_EQ(refused(logger.get(), "GRANT SELECT ON simpartner.* TO 'simpartner_reader'@'localhost'"), 1044);
  DbTarget reader_target = server_->LoggerTarget("simpartner");
  reader_target.option_file = server_->reader_options();
  auto reader = DbConnection::Open(reader_target, false);
  reader->UseDatabase(false);
  EXPECT_EQ(refused(reader.get(), "INSERT INTO LogGap (simulationID, firstStep, lastStep, missing, "
                                  "detectedAt) VALUES (1, 1, 1, 1, NOW())"),
            1142);
  EXPECT_EQ(reader->QueryInt("SELECT COUNT(*) FROM Pose", "", -1), 3);
}

// The queries of logger/analysis_queries.sql, as written (comments left out).
std::vector<std::string> AnalysisQueries() {
  std::ifstream file(std::string(SP_SOURCE_DIR) + "/logger/analysis_queries.sql");
  std::stringstream text;
  text << file.rdbuf();
  std::vector<std::string> queries;
  std::string current, line;
  while (std::getline(text, line)) {
    if (line.rfind("--", 0) == 0) continue;
    current += line + "\n";
    if (!line.empty() && line.back() == ';') {
      queries.push_back(current.substr(0, current.rfind(';')));
      current.clear();
    }
  }
  return queries;
}

TEST_F(DbTest, TheOriginalsMixedCaseQueriesRunUnchanged) {
  const SimRun run = Gen3Run(120, 77);
  WriteAll(run);

  const std::vector<std::string> queries = AnalysisQueries();
  ASSERT_EQ(queries.size(), 8u);
  // As the analysts did: the reader's user, the queries as written.
  auto db = Reader();
  db->Execute("SET @simulation = 1", "SET @simulation");
  std::vector<std::vector<std::string>> results;
  for (const std::string& q : queries) results.push_back(QueryRows(db.get(), q));

  size_t wheel1_index = 0;
  for (size_t i = 0; i < run.model.bodies.size(); ++i)
    if (run.model.bodies[i].name == "Wheel1") wheel1_index = i;
  ASSERT_EQ(results[0].size(), 120u);  // Wheel1 every step
  const state_t& last = run.states.back();
  EXPECT_EQ(std::stod(results[0].back().substr(results[0].back().find('\t') + 1)),
            last.bodies[wheel1_index].position[0]);
  EXPECT_EQ(results[1].size(), 4u * 120);  // four wheels every step
  ASSERT_EQ(results[2].size(), 4u);        // mean load per wheel
  for (int w = 0; w < 4; ++w) {
    EXPECT_EQ(results[2][static_cast<size_t>(w)].substr(0, 6), "Wheel" + std::to_string(w + 1));
    EXPECT_NE(results[2][static_cast<size_t>(w)].find("\t120"), std::string::npos);
  }
  EXPECT_EQ(results[3].size(), 120u);  // Turner angle every step
  EXPECT_EQ(results[4].size(), 4u);    // Calf1..4 at the last step
  EXPECT_EQ(results[5].size(), 1u);
  EXPECT_EQ(results[6], (std::vector<std::string>{"120\t" + std::to_string(120 * 26) + "\t" +
                                                  std::to_string(120 * 26) + "\t" +
                                                  std::to_string(120 * 25)}));
  EXPECT_TRUE(results[7].empty());  // gen3 on rigid ground: no wheel on soil
}

// A wheel rolling onto sand (sunk 1 cm at the start, driven at 0.5 m/s
// and 2 rad/s): a WheelSoil row for each step it pressed the soil, with
// the figures of the state; query 8 (traction against slip) reads them.
TEST_F(DbTest, WheelSoilRowsHoldEachWheelsSoilFigures) {
  const std::string world =
      std::string("<world name=\"Soil\">") + kSandGround +
      "<object type=\"Cylinder\" name=\"Wheel1\"><mass>50</mass><radius>0.3</radius>"
      "<length>0.2</length>" + sim::testing::Transform(0, 0.29, 0) +
      "<translationalVelocity><vx>0.5</vx><vy>0</vy><vz>0</vz></translationalVelocity>"
      "<rotationalVelocity><omegax>0</omegax><omegay>0</omegay><omegaz>-2</omegaz>"
      "</rotationalVelocity></object></world>";
  const SimRun run = WriteRun(world, 79, 30);
  auto db = Admin();
  const std::vector<std::string> rows = QueryRows(
      db.get(), "SELECT r.step, w.sinkage, w.slip, w.thrust, w.drawbarPull, w.wheelLoad, "
                "w.axleTorque, w.Fn_x, w.Fn_y, w.Fn_z, w.Fs_x, w.Fs_y, w.Fs_z, w.stuck FROM "
                "WheelSoil w JOIN SimulationRow r USING (simulationRowID) JOIN Body b ON "
                "b.bodyID = w.bodyID WHERE b.name = 'Wheel1' ORDER BY r.step");
  ASSERT_EQ(rows.size(), 30u);
  std::vector<double> slips;
  for (size_t i = 0; i < rows.size(); ++i) {
    const state_t& s = run.states[i];
    ASSERT_EQ(s.wheel_soil.size(), 1u) << "step " << s.step;
    const wheel_soil_t& w = s.wheel_soil[0];
    std::vector<double> v;
    std::stringstream fields(rows[i]);
    for (std::string field; std::getline(fields, field, '\t');) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 14u);
    // Exact: the shortest round-trip text of each double.
    EXPECT_EQ(v[0], static_cast<double>(s.step));
    const double expected[] = {w.sinkage, w.slip, w.thrust, w.drawbar_pull, w.load,
                               w.axle_torque, w.normal_force[0], w.normal_force[1],
                               w.normal_force[2], w.shear_force[0], w.shear_force[1],
                               w.shear_force[2], w.stuck ? 1.0 : 0.0};
    for (size_t k = 0; k < 13; ++k) EXPECT_EQ(v[k + 1], expected[k]) << "step " << s.step << " column " << k + 1;
    slips.push_back(w.slip);
  }
  // It sank and carried its weight's order of magnitude; it slipped.
  EXPECT_GT(run.states.back().wheel_soil[0].sinkage, 0.005);
  EXPECT_GT(run.states.back().wheel_soil[0].load, 100.0);
  EXPECT_GT(std::abs(run.states.back().wheel_soil[0].slip), 0.01);

  auto reader = Reader();
  reader->Execute("SET @simulation = 1", "SET @simulation");
  const std::vector<std::string> traction = QueryRows(reader.get(), AnalysisQueries().at(7));
  ASSERT_EQ(traction.size(), 30u);
  std::sort(slips.begin(), slips.end());
  for (size_t i = 0; i < traction.size(); ++i)
    EXPECT_EQ(std::stod(traction[i].substr(0, traction[i].find('\t'))), slips[i]) << i;
}

TEST_F(DbTest, AServerThatRefusesWritesIsAnErrorNamingServerAndCause) {
  const SimRun run = ArmRun(20, 9);
  auto writer = Writer();
  writer->Write({run.ModelRecord(), run.StateRecord(0)});
  Admin()->Execute("SET GLOBAL read_only = 1", "");
  try {
    writer->Write(run.StateRecords(2, 10));
    FAIL() << "a read-only server took the rows";
  } catch (const DbError& e) {
    EXPECT_EQ(e.kind(), DbErrorKind::kRefused);
    const std::string text = e.what();
    EXPECT_NE(text.find("unix://" + server_->socket()), std::string::npos) << text;
    EXPECT_NE(text.find("--read-only"), std::string::npos) << text;
    EXPECT_NE(text.find("INSERT INTO SimulationRow"), std::string::npos) << text;
  }
  Admin()->Execute("SET GLOBAL read_only = 0", "");
  writer->Write(run.StateRecords(2, 10));
  ExpectEveryStepOnce("simpartner", 1, 1, 10, 3, 2);
}

TEST_F(DbTest, AServerThatWentAwayIsUnreachableAndTheWriterReconnects) {
  const SimRun run = ArmRun(20, 9);
  auto writer = Writer();
  writer->Write({run.ModelRecord(), run.StateRecord(0)});
  server_->Stop();
  try {
    writer->Write(run.StateRecords(2, 10));
    FAIL() << "wrote to a stopped server";
  } catch (const DbError& e) {
    EXPECT_EQ(e.kind(), DbErrorKind::kUnreachable) << e.what();
    EXPECT_NE(std::string(e.what()).find("unix://" + server_->socket()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(writer->connected());
  try {
    writer->Write(run.StateRecords(2, 10));
    FAIL();
  } catch (const DbError& e) {
    EXPECT_EQ(e.kind(), DbErrorKind::kUnreachable) << e.what();
    EXPECT_NE(std::string(e.what()).find("connect"), std::string::npos) << e.what();
  }
  server_->Start();
  writer->Write(run.StateRecords(2, 20));
  ExpectEveryStepOnce("simpartner", 1, 1, 20, 3, 2);
}

// A COMMIT on a connection the server has dropped (a shutdown, a KILL)
// must be an error: Connector/C++ 1.1's own commit() ignores the failure,
// and a writer trusting it drops a batch the server never committed.
TEST_F(DbTest, ACommitOnADroppedConnectionIsAnErrorAndNothingIsCommitted) {
  Admin()->Execute("CREATE TABLE Probe (x INT PRIMARY KEY) ENGINE=InnoDB", "CREATE TABLE Probe");
  auto db = DbConnection::Open(server_->LoggerTarget("simpartner"), false);
  db->UseDatabase(false);
  const int64_t id = db->QueryInt("SELECT CONNECTION_ID()", "CONNECTION_ID()", -1);
  db->Begin();
  db->Execute("INSERT INTO Probe VALUES (1)", "INSERT INTO Probe");
  Admin()->Execute("KILL CONNECTION " + std::to_string(id), "KILL");
  try {
    db->Commit();
    FAIL() << "COMMIT on a killed connection succeeded";
  } catch (const DbError& e) {
    EXPECT_EQ(e.kind(), DbErrorKind::kUnreachable) << e.what();
    EXPECT_NE(std::string(e.what()).find("commit"), std::string::npos) << e.what();
  }
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Probe"), 0);
  // A transaction that does commit is there.
  auto again = DbConnection::Open(server_->LoggerTarget("simpartner"), false);
  again->UseDatabase(false);
  again->Begin();
  again->Execute("INSERT INTO Probe VALUES (2)", "INSERT INTO Probe");
  again->Commit();
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Probe"), 1);
}

TEST_F(DbTest, QueryToolListsAndExportsCsv) {
  const SimRun run = ArmRun(50, 12);
  auto writer = Writer();
  std::vector<Record> records = {run.ModelRecord()};
  for (Record& r : run.StateRecords(1, 50)) records.push_back(std::move(r));
  writer->Write(records);
  DbTarget reader_target = server_->LoggerTarget("simpartner");
  reader_target.option_file = server_->reader_options();
  auto db = DbConnection::Open(reader_target, false);
  db->UseDatabase(false);

  const Listing listing = List(db.get());
  ASSERT_EQ(listing.rows.size(), 1u) << listing.text;
  const std::vector<std::string>& fields = listing.rows[0];  // simulation 1
  ASSERT_EQ(fields.size(), 12u) << listing.text;  // end time '-': one field
  EXPECT_EQ(fields[0], "1");
  EXPECT_EQ(fields[1], "12");
  EXPECT_EQ(fields[2], "testhost");
  EXPECT_EQ(fields[3], "ArmWorld");
  EXPECT_EQ(fields[4], "ode");  // the sim's default engine
  EXPECT_EQ(fields[7], "-");
  EXPECT_EQ(fields[8], "50");  // steps
  EXPECT_EQ(fields[9], "50");  // last step
  EXPECT_EQ(fields[10], "0");  // missing
  EXPECT_EQ(fields[11], "open");

  std::ostringstream csv;
  EXPECT_EQ(ExportCsv(db.get(), ExportRequest{ExportKind::kPoses, "last", "Arm"}, csv), 50u);
  std::stringstream lines(csv.str());
  std::string header, first;
  std::getline(lines, header);
  std::getline(lines, first);
  EXPECT_EQ(header, "time_s,step,body,x_m,y_m,z_m,axis_x,axis_y,axis_z,angle_rad");
  EXPECT_EQ(first.substr(0, 14), "0.001,1,Arm,0.");
  std::ostringstream forces, joints;
  EXPECT_EQ(ExportCsv(db.get(), ExportRequest{ExportKind::kForces, "1", ""}, forces), 150u);
  EXPECT_EQ(ExportCsv(db.get(), ExportRequest{ExportKind::kJoints, "1", "Shoulder"}, joints), 50u);
  for (const auto& [request, message] :
       std::vector<std::pair<ExportRequest, std::string>>{
           {{ExportKind::kPoses, "7", ""}, "no simulation 7 in database 'simpartner'"},
           {{ExportKind::kPoses, "x", ""}, "simulation 'x' is not a simulationID"},
           {{ExportKind::kPoses, "1", "Wheel9"}, "simulation 1 has no body named 'Wheel9'"}}) {
    std::ostringstream out;
    try {
      ExportCsv(db.get(), request, out);
      FAIL() << message;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace simpartner::logger
