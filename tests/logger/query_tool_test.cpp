// simpartner-query's plots, exports (time range, every Nth step,
// velocities, unwrapped angles) and deletes, on a private MariaDB holding
// simulations logged by the real writer from the real sim library.
#include <dirent.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/text_file.h"
#include "logger_test_support.h"
#include "simpartner/child_process.h"
#include "simpartner/logger/query.h"
#include "simpartner/logger/writer.h"
#include "simpartner/viewer/xvfb.h"

namespace simpartner::logger {
namespace {

using testing::SimRun;

constexpr double kSpinRate = 5.0;  // rad/s, the wheel "Spin" turns at
constexpr double kPi = 3.14159265358979323846;

// The arm world with its wheel (in the air, 1 kg) spun at kSpinRate by a
// velocity controller with 1000 N m: at speed from the first step.
SimRun SpinRun(int steps, int64_t simulation_id, double rate = kSpinRate) {
  auto sim = sim::testing::MakeArmSim();
  sim->Reset(simulation_id);
  EXPECT_FALSE(sim->Submit(sim::testing::Command("Spin", command_t::ACTION_SET, {1000, rate})));
  return testing::MakeRun(sim.get(), steps);
}

// WorkPartner gen3 on flat ground driven straight ahead, every wheel at 4.4 rad/s.
SimRun DrivenGen3Run(int steps, int64_t simulation_id) {
  model::WorldLoadResult loaded =
      model::LoadWorldFile(std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml");
  EXPECT_TRUE(loaded.world) << loaded.diagnostics.Format();
  sim::Simulation sim(*loaded.world, Parameters(), simulation_id);
  for (int w = 1; w <= 4; ++w)
    EXPECT_FALSE(sim.Submit(sim::testing::Command("Axle" + std::to_string(w) + "Motor",
                                                  command_t::ACTION_SET, {1000, 4.4})));
  return testing::MakeRun(&sim, steps);
}

// WorkPartner gen3 standing on flat ground with its field sensors (Imu at
// 100 Hz, Lidar 4 x 221 at 12.5 Hz, Gnss, four Encoders, ...): the run and
// every reading it produced.
struct SensedRun {
  SimRun run;
  std::vector<sensor_reading_t> readings;
};
SensedRun Gen3WithReadings(int steps, int64_t simulation_id) {
  model::WorldLoadResult loaded =
      model::LoadWorldFile(std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml");
  EXPECT_TRUE(loaded.world) << loaded.diagnostics.Format();
  sim::Simulation sim(*loaded.world, Parameters(), simulation_id);
  SensedRun sensed;
  sim.FillModel(&sensed.run.model);
  sensed.run.model.host = "testhost";
  for (int i = 0; i < steps; ++i) {
    sim.Step();
    state_t s;
    sim.FillState(&s);
    sensed.run.states.push_back(s);
    for (sensor_reading_t& r : sim.TakeSensorReadings()) sensed.readings.push_back(std::move(r));
  }
  return sensed;
}

std::vector<sensor_reading_t> ReadingsOf(const SensedRun& sensed, const std::string& name) {
  std::vector<sensor_reading_t> out;
  for (const sensor_reading_t& r : sensed.readings)
    if (r.name == name) out.push_back(r);
  return out;
}

// The shipped free-fall world: a particle dropped from rest, no ground.
SimRun FreeFallRun(int steps, int64_t simulation_id) {
  model::WorldLoadResult loaded =
      model::LoadWorldFile(std::string(SP_SOURCE_DIR) + "/models/worlds/free_fall.xml");
  EXPECT_TRUE(loaded.world) << loaded.diagnostics.Format();
  sim::Simulation sim(*loaded.world, Parameters(), simulation_id);
  return testing::MakeRun(&sim, steps);
}

// CSV text -> rows of fields (lines starting with '#' and the header apart).
struct Csv {
  std::vector<std::string> comments;
  std::string header;
  std::vector<std::vector<std::string>> rows;
  double Number(size_t row, size_t column) const { return std::stod(rows.at(row).at(column)); }
};
Csv ParseCsv(const std::string& text) {
  Csv csv;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) csv.comments.push_back(line);
    else if (csv.header.empty()) csv.header = line;
    else {
      std::vector<std::string> fields;
      std::istringstream l(line);
      std::string f;
      while (std::getline(l, f, ',')) fields.push_back(f);
      csv.rows.push_back(fields);
    }
  }
  return csv;
}

class QueryToolTest : public testing::ServerTest {
 protected:
  // Logs the run through the logger's writer; `ended`: and closes it as
  // the sim stopping does.
  void Log(const SimRun& run, bool ended = true) {
    WriterOptions options;
    options.lcm_url = "udpm://test";
    options.scratch_dir = dir_.string();
    DbWriter writer(server_->LoggerTarget("simpartner"), options, [](const std::string&) {});
    std::vector<Record> records = {run.ModelRecord()};
    for (Record& r : run.StateRecords(1, static_cast<int64_t>(run.states.size())))
      records.push_back(std::move(r));
    if (ended)
      records.push_back(MakeEndedRecord(run.model.simulation_id, 2,
                                        EndedPayload{static_cast<int64_t>(run.states.size()),
                                                     EndKind::kStopped, ""}));
    writer.Write(records);
  }
  std::unique_ptr<DbConnection> Reader() {
    DbTarget target = server_->LoggerTarget("simpartner");
    target.option_file = server_->reader_options();
    std::unique_ptr<DbConnection> db = DbConnection::Open(target, false);
    db->UseDatabase(false);
    return db;
  }
  // Logs the run with its sensor readings.
  void LogWithReadings(const SensedRun& sensed) {
    WriterOptions options;
    options.lcm_url = "udpm://test";
    options.scratch_dir = dir_.string();
    DbWriter writer(server_->LoggerTarget("simpartner"), options, [](const std::string&) {});
    const SimRun& run = sensed.run;
    std::vector<Record> records = {run.ModelRecord()};
    for (Record& r : run.StateRecords(1, static_cast<int64_t>(run.states.size())))
      records.push_back(std::move(r));
    for (const sensor_reading_t& r : sensed.readings)
      records.push_back(testing::MakeRecord(RecordKind::kSensor, run.model.simulation_id, r));
    records.push_back(MakeEndedRecord(
        run.model.simulation_id, 2,
        EndedPayload{static_cast<int64_t>(run.states.size()), EndKind::kStopped, ""}));
    writer.Write(records);
  }
  Csv Readings(const ReadingsRequest& request) {
    std::ostringstream out;
    ExportReadingsCsv(Reader().get(), request, out);
    return ParseCsv(out.str());
  }
  Csv Export(const ExportRequest& request) {
    std::ostringstream out;
    ExportCsv(Reader().get(), request, out);
    return ParseCsv(out.str());
  }
  // Runs the installed-layout program with the reader's (or another) option file.
  int RunQuery(const std::vector<std::string>& args, std::string* output) {
    test_support::ProgramRun query = test_support::RunToEnd(test_support::BuiltCommand("simpartner-query", args),
                                                            (dir_ / "query.log").string(), std::chrono::seconds(120));
    *output = std::move(query.output);
    return query.status;
  }
};

// ODE's hinge angle wraps at +-pi; unwrapped, a wheel turned at a constant
// rate from the first step has angle = rate * t (2.4 turns in 3 s).
TEST_F(QueryToolTest, UnwrappedWheelAngleIsRateTimesTime) {
  Log(SpinRun(3000, 11));
  ExportRequest request;
  request.kind = ExportKind::kJoints;
  request.name = "Axle";
  request.unwrap = true;
  const Csv csv = Export(request);
  ASSERT_EQ(csv.rows.size(), 3000u);
  ASSERT_EQ(csv.comments.size(), 1u);
  EXPECT_NE(csv.comments[0].find("unwrapped"), std::string::npos);
  for (size_t i = 0; i < csv.rows.size(); i += 97) {
    const double t = csv.Number(i, 0);
    EXPECT_NEAR(std::fabs(csv.Number(i, 6)), kSpinRate * t, 0.02) << "t = " << t;
  }
  EXPECT_NEAR(std::fabs(csv.Number(2999, 6)), kSpinRate * 3.0, 0.02);
  // The default stays as it was: no comment, angles as logged.
  request.unwrap = false;
  const Csv raw = Export(request);
  EXPECT_TRUE(raw.comments.empty());
  EXPECT_EQ(raw.header, "time_s,step,joint,anchor_x_m,anchor_y_m,anchor_z_m,angle,angle2,angle3,rate,"
                        "rate2,rate3,F1x_N,F1y_N,F1z_N,T1x_Nm,T1y_Nm,T1z_Nm");
  ASSERT_EQ(raw.rows.size(), 3000u);
}

// The sim counts a wheel's turns every step and the logger stores that
// count: logged every 40th step at 100 rad/s (4 rad, more than half a turn,
// between logged steps, which no unwrapping of the logged angles can
// recover), the stored angle is still rate * t and grows at every logged step.
TEST_F(QueryToolTest, StoredContinuousAngleIsRateTimesTimeWhenLoggedSparsely) {
  constexpr double kFastRate = 100.0;  // rad/s
  constexpr int kEvery = 40;
  SimRun run = SpinRun(4000, 19, kFastRate);
  std::vector<state_t> kept;
  for (const state_t& s : run.states)
    if (s.step % kEvery == 0) kept.push_back(s);
  run.states = kept;
  Log(run);
  const std::vector<std::string> rows = QueryRows(
      Admin().get(), "SELECT r.simulationTime, p.continuousAngle, p.angle FROM simpartner.SimulationRow r "
                     "JOIN simpartner.JointPose p USING (simulationRowID) JOIN simpartner.`Joint` j "
                     "ON j.jointID = p.jointID WHERE j.name = 'Axle' ORDER BY r.step");
  ASSERT_EQ(rows.size(), 4000u / kEvery);
  double previous = 0;
  double sign = 0;
  for (const std::string& row : rows) {
    std::istringstream fields(row);
    double t = 0, continuous = 0, wrapped = 0;
    fields >> t >> continuous >> wrapped;
    if (sign == 0) sign = continuous > 0 ? 1 : -1;
    // ODE's motor runs 0.1 % slow (its CFM); a lost or extra turn is 6.3 rad.
    EXPECT_NEAR(sign * continuous, kFastRate * t, 0.1 + 0.002 * kFastRate * t) << "t = " << t;
    EXPECT_NEAR(sign * (continuous - previous), kFastRate * kEvery * 0.001, 0.1) << "t = " << t;
    EXPECT_LE(std::fabs(wrapped), kPi + 1e-9) << "angle keeps ODE's wrapped value, t = " << t;
    previous = continuous;
  }
  // --unwrap exports the stored count, also for a range that starts late.
  ExportRequest request;
  request.kind = ExportKind::kJoints;
  request.name = "Axle";
  request.unwrap = true;
  request.from = 2.0;
  request.to = 3.0;
  const Csv csv = Export(request);
  ASSERT_EQ(csv.rows.size(), 1000u / kEvery + 1);
  EXPECT_NEAR(sign * csv.Number(0, 6), kFastRate * 2.0, 0.5);
  EXPECT_NEAR(sign * csv.Number(csv.rows.size() - 1, 6), kFastRate * 3.0, 0.7);
}

TEST_F(QueryToolTest, TimeRangeAndEveryNthStep) {
  Log(SpinRun(3000, 12));
  ExportRequest request;
  request.kind = ExportKind::kJoints;
  request.name = "Axle";
  request.from = 1.0;
  request.to = 2.0;
  request.every = 10;
  request.unwrap = true;
  const Csv csv = Export(request);
  // Steps 1000..2000 (t = step x 1 ms) are in the range: 1001, every 10th
  // from the first: 101.
  ASSERT_EQ(csv.rows.size(), 101u);
  EXPECT_EQ(csv.rows.front()[1], "1000");
  EXPECT_EQ(csv.rows.back()[1], "2000");
  for (size_t i = 1; i < csv.rows.size(); ++i)
    EXPECT_EQ(std::stoll(csv.rows[i][1]) - std::stoll(csv.rows[i - 1][1]), 10);
  // Unwrapped from the start, not from --from: still rate * t.
  EXPECT_NEAR(std::fabs(csv.Number(0, 6)), kSpinRate * 1.0, 0.02);
  EXPECT_NEAR(std::fabs(csv.Number(100, 6)), kSpinRate * 2.0, 0.02);
  // All bodies: three per kept step.
  ExportRequest poses;
  poses.from = 0.5;
  poses.to = 0.6;
  poses.every = 50;
  EXPECT_EQ(Export(poses).rows.size(), 3u * 3u);  // steps 500, 550, 600
}

// Free fall from rest: vy = -g t (the logger stores no velocities; they
// come from central differences of the logged heights).
TEST_F(QueryToolTest, VelocitiesOfAFreeFallAreMinusGTimesT) {
  Log(FreeFallRun(1000, 13));
  ExportRequest request;
  request.velocities = true;
  request.name = "TestParticle";
  const Csv csv = Export(request);
  ASSERT_EQ(csv.rows.size(), 1000u);
  ASSERT_EQ(csv.comments.size(), 1u);
  EXPECT_NE(csv.comments[0].find("central differences"), std::string::npos);
  EXPECT_NE(csv.header.find("vx_m_s,vy_m_s,vz_m_s"), std::string::npos) << csv.header;
  for (size_t i = 0; i < csv.rows.size(); i += 111) {
    const double t = csv.Number(i, 0);
    EXPECT_NEAR(csv.Number(i, 11), -9.81 * t, 0.02) << "t = " << t;
    EXPECT_NEAR(csv.Number(i, 10), 0.0, 1e-9);
  }
  // A range reads the steps around it: the first row's difference is central too.
  request.from = 0.5;
  request.to = 0.5;
  const Csv one = Export(request);
  ASSERT_EQ(one.rows.size(), 1u);
  EXPECT_NEAR(one.Number(0, 11), -9.81 * 0.5, 0.006);
  request.kind = ExportKind::kForces;
  EXPECT_THROW(Export(request), Error);
  try {
    MakePlot(Reader().get(), PlotRequest{PlotKind::kWheelForces, "last", ""});
    ADD_FAILURE() << "a world without wheels plotted wheel forces";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "simulation 1 (FreeFall) has no body named Wheel*; name one with --body");
  }
}

bool IsPng(const std::filesystem::path& path, uintmax_t* size) {
  std::ifstream in(path, std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  *size = std::filesystem::exists(path) ? std::filesystem::file_size(path) : 0;
  return in && std::string(signature, 8) == "\x89PNG\r\n\x1a\n";
}

TEST_F(QueryToolTest, PlotsArePngsOfWhatTheySay) {
  Log(SpinRun(2000, 14));
  auto db = Reader();
  // SP_PLOT_DIR keeps the PNGs for a look.
  const char* keep = std::getenv("SP_PLOT_DIR");
  const std::filesystem::path out = keep != nullptr ? std::filesystem::path(keep) : dir_;
  std::filesystem::create_directories(out);
  struct Case {
    PlotKind kind;
    std::string name, file;
    size_t series;
  };
  for (const Case& c : {Case{PlotKind::kAngle, "Axle", "angle.png", 1},
                        Case{PlotKind::kRate, "Axle", "rate.png", 1},
                        Case{PlotKind::kForce, "Shoulder", "force.png", 4},
                        Case{PlotKind::kPosition, "Arm", "position.png", 3},
                        Case{PlotKind::kVelocity, "Wheel", "velocity.png", 4},
                        Case{PlotKind::kWheelForces, "", "wheels.png", 1},
                        Case{PlotKind::kTrack, "", "track.png", 3}}) {
    PlotRequest request;
    request.kind = c.kind;
    request.name = c.name;
    const Plot plot = MakePlot(db.get(), request);
    EXPECT_EQ(plot.series.size(), c.series) << c.file;
    for (const Series& s : plot.series)
      EXPECT_EQ(s.x.size(), s.style == "mark" ? 1u : 2000u) << c.file << " " << s.title;
    DrawPlotPng(plot, (out / c.file).string());
    uintmax_t size = 0;
    EXPECT_TRUE(IsPng(out / c.file, &size)) << c.file;
    EXPECT_GT(size, 10000u) << c.file;
  }
  // The angle plot is continuous: its last point is rate * 2 s.
  PlotRequest angle;
  angle.kind = PlotKind::kAngle;
  angle.name = "Axle";
  const Plot plot = MakePlot(db.get(), angle);
  EXPECT_NEAR(std::fabs(plot.series[0].y.back()), kSpinRate * 2.0, 0.02);
  // The wheel-forces plot found the body named Wheel; the track is the robot's first body.
  EXPECT_EQ(MakePlot(db.get(), PlotRequest{PlotKind::kWheelForces, "last", ""}).series[0].title, "Wheel");
  const Plot track = MakePlot(db.get(), PlotRequest{PlotKind::kTrack, "last", ""});
  EXPECT_NE(track.title.find("track of Base"), std::string::npos);
  // The base stands still: a dot marked start and end in a window of a metre.
  ASSERT_EQ(track.series.size(), 3u);
  EXPECT_EQ(track.series[1].title, "start");
  EXPECT_EQ(track.series[2].title, "end");
  EXPECT_EQ(track.series[1].x[0], track.series[0].x.front());
  EXPECT_EQ(track.series[2].y[0], track.series[0].y.back());
  const AxisRanges window = EqualAxesRanges(track);
  EXPECT_NEAR(window.x_max - window.x_min, kTrackMinExtent, 1e-9);
  EXPECT_NEAR(window.y_max - window.y_min, kTrackMinExtent, 1e-9);
}

// The four wheels of gen3 each in a panel of its own, in a style of its
// own (two wheels carry the same load and drew over the other two, issue
// 23), and their loads carry the robot.
TEST_F(QueryToolTest, WheelForcesShowEveryWheelAndCarryTheRobot) {
  const SimRun driven = DrivenGen3Run(1500, 61);
  Log(driven);
  const Plot plot = MakePlot(Reader().get(), PlotRequest{PlotKind::kWheelForces, "last", ""});
  ASSERT_EQ(plot.series.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(plot.series[i].title, "Wheel" + std::to_string(i + 1));
  EXPECT_TRUE(plot.panels);
  const std::string script = GnuplotScript(plot, "data.txt");
  EXPECT_NE(script.find("set multiplot layout 2,2"), std::string::npos) << script;
  std::set<std::string> styles;
  for (size_t at = script.find(" with "); at != std::string::npos; at = script.find(" with ", at + 1))
    styles.insert(script.substr(at, script.find(" notitle", at) - at));
  EXPECT_EQ(styles.size(), 4u) << script;
  // Rolling on at constant speed, the wheels carry the robot's weight
  // (the mean of the last half second).
  double mass = 0;
  for (const robot_t& r : driven.model.robots) mass += r.total_mass;
  double load = 0;
  for (const Series& wheel : plot.series)
    for (size_t i = wheel.y.size() - 500; i < wheel.y.size(); ++i) load += wheel.y[i] / 500;
  EXPECT_NEAR(load, mass * 9.81, 0.02 * mass * 9.81);
}

// Driven straight ahead, the chassis' track is a line: seen from above in
// a window at most three times as long as wide (not a strip), equal scale,
// with every point inside.
TEST_F(QueryToolTest, TrackOfAStraightRunIsAWindowNotAStrip) {
  Log(DrivenGen3Run(1500, 62));
  const Plot plot = MakePlot(Reader().get(), PlotRequest{PlotKind::kTrack, "last", ""});
  ASSERT_EQ(plot.series.size(), 3u);
  const Series& track = plot.series[0];
  EXPECT_TRUE(plot.equal_axes);
  const AxisRanges window = EqualAxesRanges(plot);
  const double dx = window.x_max - window.x_min, dy = window.y_max - window.y_min;
  EXPECT_LE(std::max(dx, dy) / std::min(dx, dy), kMaxEqualAxesAspect + 1e-9);
  EXPECT_GE(std::min(dx, dy), kTrackMinExtent);
  double x_lo = 1e9, x_hi = -1e9, y_lo = 1e9, y_hi = -1e9;
  for (size_t i = 0; i < track.x.size(); ++i) {
    x_lo = std::min(x_lo, track.x[i]);
    x_hi = std::max(x_hi, track.x[i]);
    y_lo = std::min(y_lo, track.y[i]);
    y_hi = std::max(y_hi, track.y[i]);
  }
  EXPECT_GE(x_lo, window.x_min);
  EXPECT_LE(x_hi, window.x_max);
  EXPECT_GE(y_lo, window.y_min);
  EXPECT_LE(y_hi, window.y_max);
  // It drove: over a metre one way, a straight line (sideways a hundredth of that).
  const double along = std::max(x_hi - x_lo, y_hi - y_lo), across = std::min(x_hi - x_lo, y_hi - y_lo);
  EXPECT_GT(along, 1.0);
  EXPECT_LT(across, 0.01 * along);
  const std::string script = GnuplotScript(plot, "data.txt");
  EXPECT_NE(script.find("set size ratio -1"), std::string::npos) << script;
}

// The arrays that Python's read_logged and the plots read hold the numbers
// of the row-by-row export, step for step: poses with velocities, contact
// forces, joints with continuous angles.
TEST_F(QueryToolTest, ArraysHoldTheNumbersOfTheExport) {
  Log(SpinRun(600, 51));
  auto db = Reader();
  LoggedRunRequest all;
  all.velocities = true;
  all.forces = true;
  const LoggedRun run = ReadLoggedRun(db.get(), all);
  ASSERT_EQ(run.time.size(), 600u);
  EXPECT_EQ(run.step.front(), 1);
  EXPECT_EQ(run.step.back(), 600);
  auto compare = [&](ExportRequest request, const std::vector<PartArray>& arrays) {
    size_t i = 0;
    ReadExport(db.get(), request, [&](const ExportStep& step) {
      ASSERT_LT(i, run.time.size());
      EXPECT_EQ(step.step, run.step[i]);
      ASSERT_EQ(step.rows.size(), arrays.size());
      for (size_t p = 0; p < arrays.size(); ++p) {
        EXPECT_EQ(step.rows[p].name, arrays[p].name);
        const std::vector<double>& values = step.rows[p].values;
        for (size_t k = 0; k < values.size(); ++k)
          EXPECT_NEAR(arrays[p].values[i * values.size() + k], values[k], 1e-9 * (1 + std::fabs(values[k])))
              << arrays[p].name << " step " << step.step << " column " << k;
      }
      ++i;
    });
    EXPECT_EQ(i, run.time.size());
  };
  ExportRequest poses;
  poses.velocities = true;
  compare(poses, run.poses);
  ExportRequest forces;
  forces.kind = ExportKind::kForces;
  compare(forces, run.forces);
  ExportRequest joints;
  joints.kind = ExportKind::kJoints;
  joints.unwrap = true;
  compare(joints, run.joints);
  // The wheel turned at kSpinRate from the first step: angle = rate * t.
  ASSERT_EQ(run.joints[1].name, "Axle");
  EXPECT_NEAR(std::fabs(run.joints[1].values[599 * 15 + 3]), kSpinRate * 0.6, 0.02);
}

// A time range is the whole run's steps in it, velocities central at its
// ends too; a body filter is that body's array; bad names and ranges are errors.
TEST_F(QueryToolTest, ArraysOfATimeRangeAndOfOneBody) {
  Log(SpinRun(600, 52));
  auto db = Reader();
  LoggedRunRequest all;
  all.velocities = true;
  const LoggedRun run = ReadLoggedRun(db.get(), all);
  LoggedRunRequest part = all;
  part.from = 0.2005;
  part.to = 0.3005;
  const LoggedRun slice = ReadLoggedRun(db.get(), part);
  ASSERT_EQ(slice.time.size(), 100u);  // steps 201 to 300
  EXPECT_EQ(slice.step.front(), 201);
  EXPECT_EQ(slice.step.back(), 300);
  for (size_t p = 0; p < run.poses.size(); ++p)
    EXPECT_EQ(slice.poses[p].values, std::vector<double>(run.poses[p].values.begin() + 200 * 10,
                                                         run.poses[p].values.begin() + 300 * 10))
        << run.poses[p].name;
  for (size_t j = 0; j < run.joints.size(); ++j)
    EXPECT_EQ(slice.joints[j].values, std::vector<double>(run.joints[j].values.begin() + 200 * 15,
                                                          run.joints[j].values.begin() + 300 * 15));
  LoggedRunRequest wheel = all;
  wheel.bodies = {false, {"Wheel"}};
  wheel.joints = {false, {}};
  const LoggedRun one = ReadLoggedRun(db.get(), wheel);
  ASSERT_EQ(one.poses.size(), 1u);
  EXPECT_TRUE(one.joints.empty());
  EXPECT_EQ(one.poses[0].name, "Wheel");
  EXPECT_EQ(one.poses[0].values, run.poses[2].values);
  wheel.bodies.names = {"Wheell"};
  try {
    ReadLoggedRun(db.get(), wheel);
    ADD_FAILURE() << "read an unknown body";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "simulation 1 has no body named 'Wheell' (did you mean 'Wheel'?)");
  }
  part.from = 0.5;
  part.to = 0.25;
  EXPECT_THROW(ReadLoggedRun(db.get(), part), Error);
}

// Simulations logged before the sim counted turns have no continuous
// angle: the arrays unwrap the logged angles from the first step, also
// for a range that starts late.
TEST_F(QueryToolTest, ArraysUnwrapAnglesLoggedWithoutTheirTurns) {
  Log(SpinRun(3000, 53));
  Admin()->Execute("UPDATE JointPose SET continuousAngle = NULL, continuousAngle2 = NULL, "
                   "continuousAngle3 = NULL",
                   "forget the continuous angles");
  LoggedRunRequest late;
  late.from = 2.0;
  late.joints = {false, {"Axle"}};
  late.poses = false;
  const LoggedRun run = ReadLoggedRun(Reader().get(), late);
  ASSERT_EQ(run.joints.size(), 1u);
  ASSERT_EQ(run.time.size(), 1001u);  // steps 2000 to 3000
  for (size_t i = 0; i < run.time.size(); i += 100)
    EXPECT_NEAR(std::fabs(run.joints[0].values[i * 15 + 3]), kSpinRate * run.time[i], 0.02)
        << "t = " << run.time[i];
}

TEST_F(QueryToolTest, UnknownNamesAndSimulationsAreNamed) {
  Log(SpinRun(20, 15));
  auto db = Reader();
  auto message = [&](PlotRequest request) {
    try {
      MakePlot(db.get(), request);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(PlotRequest{PlotKind::kAngle, "last", "Axel"}),
            "simulation 1 has no joint named 'Axel' (did you mean 'Axle'?)");
  EXPECT_EQ(message(PlotRequest{PlotKind::kPosition, "last", "arm"}),
            "simulation 1 has no body named 'arm' (did you mean 'Arm'?)");
  EXPECT_EQ(message(PlotRequest{PlotKind::kPosition, "99", "Arm"}),
            "no simulation 99 in database 'simpartner' (simpartner-query list shows them)");
  EXPECT_EQ(message(PlotRequest{PlotKind::kPosition, "running", "Arm"}),
            "no simulation is running (every simulation in database 'simpartner' has ended; "
            "'last' is the newest)");
  EXPECT_EQ(message(PlotRequest{PlotKind::kAngle, "last", ""}),
            "plot needs --joint NAME (simpartner-query names SIM lists them)");
  EXPECT_THROW(ParsePlotKind("angel"), Error);
  try {
    ParsePlotKind("angel");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'angle'"), std::string::npos) << e.what();
  }
}

// SQL reads a kind's readings by name from its view (schema version 11):
// the values as the reading had them, in the kind's columns.
TEST_F(QueryToolTest, EachSensorKindHasAViewWithNamedColumns) {
  const SensedRun sensed = Gen3WithReadings(200, 32);
  LogWithReadings(sensed);
  const std::unique_ptr<DbConnection> db = Reader();
  const std::vector<sensor_reading_t> imu = ReadingsOf(sensed, "Imu");
  ASSERT_GE(imu.size(), 10u);
  std::unique_ptr<sql::ResultSet> rows =
      db->Query("SELECT step, sensor, ax, az, qw FROM ImuReading ORDER BY step", "ImuReading");
  size_t i = 0;
  while (rows->next()) {
    ASSERT_LT(i, imu.size());
    EXPECT_EQ(rows->getInt64("step"), imu[i].step);
    EXPECT_EQ(std::string(rows->getString("sensor")), "Imu");
    EXPECT_EQ(static_cast<double>(rows->getDouble("ax")), imu[i].values[0]) << i;
    EXPECT_EQ(static_cast<double>(rows->getDouble("az")), imu[i].values[2]) << i;
    EXPECT_EQ(static_cast<double>(rows->getDouble("qw")), imu[i].values[6]) << i;
    ++i;
  }
  EXPECT_EQ(i, imu.size());
  const std::vector<sensor_reading_t> encoder = ReadingsOf(sensed, "Encoder1");
  ASSERT_FALSE(encoder.empty());
  rows = db->Query("SELECT `count`, count_rate FROM EncoderReading WHERE sensor = 'Encoder1' "
                   "ORDER BY step DESC LIMIT 1",
                   "EncoderReading");
  ASSERT_TRUE(rows->next());
  EXPECT_EQ(static_cast<double>(rows->getDouble("count")), encoder.back().values[0]);
  EXPECT_EQ(static_cast<double>(rows->getDouble("count_rate")), encoder.back().values[1]);
  EXPECT_EQ(db->QueryInt("SELECT COUNT(*) FROM LidarReading", "LidarReading", -1),
            static_cast<int64_t>(ReadingsOf(sensed, "Lidar").size()));
  EXPECT_EQ(db->QueryInt("SELECT COUNT(*) FROM GnssReading WHERE fix = 1", "GnssReading", -1),
            static_cast<int64_t>(ReadingsOf(sensed, "Gnss").size()));
}

TEST_F(QueryToolTest, ReadingsOfOneSensorUnderItsKindsNames) {
  const SensedRun sensed = Gen3WithReadings(200, 31);
  LogWithReadings(sensed);
  const std::vector<sensor_reading_t> imu = ReadingsOf(sensed, "Imu");
  ASSERT_GE(imu.size(), 10u);  // 100 Hz for 0.2 s
  const Csv csv = Readings(ReadingsRequest{"last", "Imu"});
  EXPECT_EQ(csv.header, "time_s,step,sensor,ax,ay,az,wx,wy,wz,qw,qx,qy,qz");
  ASSERT_EQ(csv.rows.size(), imu.size());
  for (size_t i = 0; i < imu.size(); ++i) {
    ASSERT_EQ(csv.rows[i].size(), 13u);
    EXPECT_EQ(std::stoll(csv.rows[i][1]), imu[i].step);
    EXPECT_EQ(csv.rows[i][2], "Imu");
    for (size_t k = 0; k < 10; ++k) EXPECT_EQ(csv.Number(i, 3 + k), imu[i].values[k]) << i << "," << k;
  }
  // Standing (y up): the specific force is +g up.
  EXPECT_NEAR(csv.Number(csv.rows.size() - 1, 4), 9.81, 1.0);

  // The lidar: a row per layer, its 221 ranges after the layer number.
  const std::vector<sensor_reading_t> lidar = ReadingsOf(sensed, "Lidar");
  ASSERT_GE(lidar.size(), 1u);
  const Csv layers = Readings(ReadingsRequest{"last", "Lidar"});
  EXPECT_EQ(layers.header.rfind("time_s,step,sensor,layer,range_0,range_1,", 0), 0u)
      << layers.header;
  EXPECT_NE(layers.header.find(",range_220"), std::string::npos);
  EXPECT_EQ(layers.header.find(",range_221"), std::string::npos);
  ASSERT_EQ(layers.rows.size(), 4 * lidar.size());
  for (size_t layer = 0; layer < 4; ++layer) {
    EXPECT_EQ(layers.rows[layer][3], std::to_string(layer));
    EXPECT_EQ(layers.Number(layer, 4 + 17), lidar[0].values[layer * 221 + 17]);
  }

  // The range of time, and a sensor with no readings keeps its header.
  const Csv late = Readings(ReadingsRequest{"last", "Imu", 0.1, 0.15});
  ASSERT_FALSE(late.rows.empty());
  for (size_t i = 0; i < late.rows.size(); ++i) {
    EXPECT_GE(late.Number(i, 0), 0.1);
    EXPECT_LE(late.Number(i, 0), 0.15);
  }
  const Csv none = Readings(ReadingsRequest{"last", "Imu", 5, 6});
  EXPECT_EQ(none.header, "time_s,step,sensor,ax,ay,az,wx,wy,wz,qw,qx,qy,qz");
  EXPECT_TRUE(none.rows.empty());
}

TEST_F(QueryToolTest, ReadingsOfEverySensorOneValueARow) {
  const SensedRun sensed = Gen3WithReadings(100, 32);
  LogWithReadings(sensed);
  const Csv csv = Readings(ReadingsRequest{"last", ""});
  EXPECT_EQ(csv.header, "time_s,step,sensor,kind,layer,column,value");
  size_t values = 0;
  for (const sensor_reading_t& r : sensed.readings) values += r.values.empty() ? 1 : r.values.size();
  EXPECT_EQ(csv.rows.size(), values);
  const std::vector<sensor_reading_t> encoder = ReadingsOf(sensed, "Encoder2");
  ASSERT_FALSE(encoder.empty());
  bool found = false;
  for (size_t i = 0; i < csv.rows.size() && !found; ++i) {
    const std::vector<std::string>& row = csv.rows[i];
    if (row[2] != "Encoder2" || row[5] != "count_rate" || std::stoll(row[1]) != encoder[0].step)
      continue;
    found = true;
    EXPECT_EQ(row[3], "encoder");
    EXPECT_EQ(row[4], "0");
    EXPECT_EQ(csv.Number(i, 6), encoder[0].values[1]);
  }
  EXPECT_TRUE(found);
  try {
    Readings(ReadingsRequest{"last", "Imuu"});
    ADD_FAILURE() << "no error for a sensor the simulation lacks";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "simulation 1 has no sensor named 'Imuu' (did you mean 'Imu'?)");
  }
}

// A new simulation on the same host closes the one before (the logger's
// rule); an open one beside a newer closed one is from another host.
SimRun OnOtherHost(SimRun run) {
  run.model.host = "otherhost";
  return run;
}

TEST_F(QueryToolTest, RunningIsTheNewestOpenSimulation) {
  Log(OnOtherHost(SpinRun(20, 16)), false);
  Log(SpinRun(30, 17), true);
  ExportRequest request;
  request.simulation = "running";
  request.name = "Arm";
  EXPECT_EQ(Export(request).rows.size(), 20u);
  request.simulation = "last";
  EXPECT_EQ(Export(request).rows.size(), 30u);
}

TEST_F(QueryToolTest, DeleteRemovesOnlyThatSimulationAndNeedsAnAdministrator) {
  Log(SpinRun(40, 21));
  Log(SpinRun(50, 22));
  Log(SpinRun(60, 23));
  auto rows_of = [&](int sim) {
    return QueryInt("SELECT COUNT(*) FROM SimulationRow r JOIN Pose p USING (simulationRowID) "
                    "WHERE r.simulationID = " + std::to_string(sim)) +
           QueryInt("SELECT COUNT(*) FROM SimulationRow r JOIN JointPose p USING (simulationRowID) "
                    "WHERE r.simulationID = " + std::to_string(sim)) +
           QueryInt("SELECT COUNT(*) FROM Body WHERE simulationID = " + std::to_string(sim)) +
           QueryInt("SELECT COUNT(*) FROM Robot WHERE simulationID = " + std::to_string(sim));
  };
  const int64_t before1 = rows_of(1), before3 = rows_of(3);
  // The arm world: 3 bodies and 2 joints a step, one robot.
  EXPECT_EQ(rows_of(2), 50 * 5 + 3 + 1);
  // The reader has no DELETE: refused, nothing deleted.
  try {
    DeleteSimulation(Reader().get(), "2", false);
    ADD_FAILURE() << "the reader deleted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("deleting needs an administrator"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Nothing was deleted"), std::string::npos) << e.what();
  }
  EXPECT_EQ(rows_of(2), 50 * 5 + 3 + 1);
  // The logger's own user neither.
  {
    std::unique_ptr<DbConnection> logger_db = DbConnection::Open(server_->LoggerTarget("simpartner"), false);
    logger_db->UseDatabase(false);
    EXPECT_THROW(DeleteSimulation(logger_db.get(), "2", false), Error);
  }
  const DeleteSummary done = DeleteSimulation(Admin().get(), "2", false);
  EXPECT_EQ(done.simulations, std::vector<uint32_t>{2});
  EXPECT_EQ(done.steps, 50u);
  EXPECT_EQ(rows_of(2), 0);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Simulation WHERE simulationID = 2"), 0);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM `Joint` WHERE simulationID = 2"), 0);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM RobotComponent c LEFT JOIN Robot r USING (robotID) "
                     "WHERE r.robotID IS NULL"), 0);
  EXPECT_EQ(rows_of(1), before1);
  EXPECT_EQ(rows_of(3), before3);
  EXPECT_THROW(DeleteSimulation(Admin().get(), "2", false), Error);  // no simulation 2
}

TEST_F(QueryToolTest, PruneKeepsTheNewestAndOpenOnes) {
  Log(OnOtherHost(SpinRun(10, 31)), false);  // open: kept whatever its age
  Log(SpinRun(10, 32));
  Log(SpinRun(10, 33));
  Log(SpinRun(10, 34));
  const DeleteSummary done = PruneSimulations(Admin().get(), 2);
  // The newest two (4, 3) stay, and 1 (still open); 2 goes.
  EXPECT_EQ(done.simulations, std::vector<uint32_t>{2});
  EXPECT_EQ(QueryRows(Admin().get(), "SELECT simulationID FROM Simulation ORDER BY simulationID"),
            (std::vector<std::string>{"1", "3", "4"}));
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM SimulationRow"), 30);
  EXPECT_EQ(PruneSimulations(Admin().get(), 1).simulations, std::vector<uint32_t>{3});
  EXPECT_THROW(DeleteSimulation(Admin().get(), "1", false), Error);  // open
  EXPECT_EQ(DeleteSimulation(Admin().get(), "1", true).steps, 10u);
}

// The forms CREATE_OPTIONS takes (MariaDB 10.11 quotes the value; the
// earlier parse looked for it unquoted and reported every table as plain).
TEST(PageCompressedOption, ReadsTheOptionInItsForms) {
  EXPECT_TRUE(PageCompressedOption("`page_compressed`='1'"));
  EXPECT_TRUE(PageCompressedOption("row_format=dynamic `page_compressed`='1' `page_compression_level`='6'"));
  EXPECT_TRUE(PageCompressedOption("`page_compressed`=1"));
  EXPECT_TRUE(PageCompressedOption("`page_compressed`='on'"));
  EXPECT_FALSE(PageCompressedOption("`page_compressed`='0'"));
  EXPECT_FALSE(PageCompressedOption("`page_compressed`='off'"));
  EXPECT_FALSE(PageCompressedOption("`page_compression_level`='1'"));
  EXPECT_FALSE(PageCompressedOption(""));
}

// `compress on|off` rebuilds the per-step tables with InnoDB page
// compression and back: the server then reports PAGE_COMPRESSED, `storage`
// says so, every row reads back the same to the bit, and the writer goes on
// writing into them. Only an administrator may do it; bad uses change nothing.
TEST_F(QueryToolTest, CompressionRebuildsTheStepTablesWithTheSameRows) {
  Log(SpinRun(1500, 41));
  const std::vector<std::string> tables = {"SimulationRow", "Pose", "ForceAndTorque", "JointPose"};
  // The table's options as the server has them, not as the tool parses them.
  auto compressed = [&](const std::string& table) {
    const std::vector<std::string> options = QueryRows(
        Admin().get(), "SELECT LOWER(CREATE_OPTIONS) FROM information_schema.TABLES WHERE "
                       "TABLE_SCHEMA = 'simpartner' AND TABLE_NAME = '" + table + "'");
    EXPECT_EQ(options.size(), 1u) << table;
    // MariaDB 10.11 writes `page_compressed`='1'.
    return !options.empty() && (options[0].find("page_compressed`='1'") != std::string::npos ||
                                options[0].find("page_compressed`=1") != std::string::npos);
  };
  // Every stored value of the two big tables, as text, folded into one number each.
  auto checksum = [&] {
    std::vector<std::string> sums = QueryRows(Admin().get(),
                     "SELECT COUNT(*), SUM(CRC32(CONCAT_WS(',', simulationRowID, bodyID, x, y, z, "
                     "axisX, axisY, axisZ, angle))) FROM Pose");
    const std::vector<std::string> joints = QueryRows(Admin().get(),
                     "SELECT COUNT(*), SUM(CRC32(CONCAT_WS(',', simulationRowID, jointID, anchorx, "
                     "anchory, anchorz, angle, angle2, angle3, rate, rate2, rate3, F_x, F_y))) "
                     "FROM JointPose");
    sums.insert(sums.end(), joints.begin(), joints.end());
    return sums;
  };
  const std::vector<std::string> before = checksum();
  ASSERT_EQ(before.size(), 2u);
  EXPECT_EQ(before[0].substr(0, before[0].find('\t')), std::to_string(1500 * 3));
  // `storage`'s line for a table: rows, bytes, on disk, compressed (yes/no).
  auto storage_line = [&](const std::string& table) {
    std::string output;
    EXPECT_EQ(RunQuery({"storage", "--db-options", server_->admin_options()}, &output), 0) << output;
    std::istringstream lines(output);
    std::string line;
    while (std::getline(lines, line)) {
      std::istringstream fields(line);
      std::string name, rest;
      fields >> name;
      std::getline(fields, rest);
      if (name == table) return rest;
    }
    ADD_FAILURE() << "no line for " << table << " in:\n" << output;
    return std::string();
  };
  auto storage_says = [&](const std::string& table, const std::string& compression) {
    std::istringstream fields(storage_line(table));
    long long rows = -1, bytes = -1, disk = -1;
    std::string last;
    fields >> rows >> bytes >> disk >> last;
    return bytes > 0 && last == compression;
  };
  {
    std::istringstream pose(storage_line("Pose"));
    long long rows = 0;
    pose >> rows;
    // InnoDB's row count is an estimate, even after ANALYZE TABLE.
    EXPECT_NEAR(static_cast<double>(rows), 1500.0 * 3, 1500.0 * 3 * 0.5);
  }
  EXPECT_TRUE(storage_says("Pose", "no"));

  std::string output;
  EXPECT_EQ(RunQuery({"compress", "on", "--db-options", server_->reader_options()}, &output), 1);
  EXPECT_NE(output.find("needs the administrator"), std::string::npos) << output;
  EXPECT_EQ(RunQuery({"compress", "maybe", "--db-options", server_->admin_options()}, &output), 2);
  EXPECT_NE(output.find("compress: value 'maybe' is not on or off"), std::string::npos) << output;
  EXPECT_EQ(RunQuery({"compress", "--db-options", server_->admin_options()}, &output), 2);
  EXPECT_NE(output.find("compress needs on|off"), std::string::npos) << output;
  EXPECT_EQ(RunQuery({"storage", "7", "--db-options", server_->admin_options()}, &output), 2);
  EXPECT_NE(output.find("unexpected argument '7' (storage takes no arguments)"), std::string::npos) << output;
  for (const std::string& t : tables) EXPECT_FALSE(compressed(t)) << t;

  EXPECT_EQ(RunQuery({"compress", "on", "--db-options", server_->admin_options()}, &output), 0) << output;
  EXPECT_NE(output.find("page compression on for SimulationRow Pose ForceAndTorque JointPose"),
            std::string::npos)
      << output;
  for (const std::string& t : tables) {
    EXPECT_TRUE(compressed(t)) << t;
    EXPECT_TRUE(storage_says(t, "yes")) << t;
  }
  EXPECT_EQ(checksum(), before);
  // The logger's writer goes on into the compressed tables.
  Log(SpinRun(200, 42));
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM SimulationRow r JOIN Pose p USING (simulationRowID) "
                     "WHERE r.simulationID = 2"),
            200 * 3);

  EXPECT_EQ(RunQuery({"compress", "off", "--db-options", server_->admin_options()}, &output), 0) << output;
  for (const std::string& t : tables) {
    EXPECT_FALSE(compressed(t)) << t;
    EXPECT_TRUE(storage_says(t, "no")) << t;
  }
  EXPECT_EQ(QueryRows(Admin().get(), "SELECT COUNT(*), SUM(CRC32(CONCAT_WS(',', simulationRowID, "
                                     "bodyID, x, y, z, axisX, axisY, axisZ, angle))) FROM Pose "
                                     "JOIN SimulationRow USING (simulationRowID) WHERE simulationID = 1"),
            std::vector<std::string>{before[0]});
}

// Processes whose name starts with `name` and that run on `display` (their
// environment says DISPLAY=display): what a plot window leaves behind.
std::vector<pid_t> ProcessesOnDisplay(const std::string& name, const std::string& display) {
  std::vector<pid_t> found;
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return found;
  while (const dirent* entry = ::readdir(proc)) {
    const std::string pid = entry->d_name;
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string comm;
    std::getline(std::ifstream("/proc/" + pid + "/comm"), comm);
    if (comm.rfind(name, 0) != 0) continue;
    std::ifstream environ("/proc/" + pid + "/environ");
    std::string variable;
    while (std::getline(environ, variable, '\0'))
      if (variable == "DISPLAY=" + display) found.push_back(static_cast<pid_t>(std::stol(pid)));
  }
  ::closedir(proc);
  return found;
}

// With a DISPLAY and no -o, a plot is a gnuplot window titled like the plot
// (on a private Xvfb here): what it shows is a drawn plot (a light page, a
// coloured curve), the command waits while it is open, and pressing q in it
// ends the command with nothing left running.
TEST_F(QueryToolTest, PlotWindowShowsThePlotAndTheCommandEndsWhenItIsClosed) {
  Log(SpinRun(2000, 61));
  const std::filesystem::path screen_dir = dir_ / "screen";
  std::filesystem::create_directories(screen_dir);
  viewer::XvfbServer xvfb(1024, 768, (dir_ / "xvfb.log").string(), screen_dir.string());
  const std::string query_log = (dir_ / "window.log").string();
  ::setenv("DISPLAY", xvfb.display().c_str(), 1);
  ChildProcess query(test_support::BuiltCommand("simpartner-query", {"plot", "rate", "last", "--joint", "Axle",
                                                                     "--db-options",
                                                                     server_->reader_options()}),
                     query_log);
  ::unsetenv("DISPLAY");
  auto query_said = [&] { return test_support::ReadText(query_log); };
  // `expected_status` < 0: any (a search that may find nothing yet).
  auto xdotool = [&](const std::vector<std::string>& args, int expected_status = 0) {
    const test_support::ProgramRun run =
        test_support::RunXdotool(xvfb.display(), args, (dir_ / "xdotool.log").string());
    if (expected_status >= 0) {
      EXPECT_EQ(run.status, expected_status) << args[0];
    }
    return run.output.substr(0, run.output.find('\n'));
  };
  // The command names the window it opens: "simpartner-query: TITLE in a window; ...".
  std::string title;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::string window;
  while (std::chrono::steady_clock::now() < deadline && query.running()) {
    const std::string said = query_said();
    const std::string prefix = "simpartner-query: ", suffix = " in a window; close it";
    const size_t end = said.find(suffix);
    if (title.empty() && end != std::string::npos && said.rfind(prefix, 0) == 0)
      title = said.substr(prefix.size(), end - prefix.size());
    if (!title.empty()) {
      window = xdotool({"search", "--name", "rate of joint Axle"}, -1);
      if (!window.empty()) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_FALSE(window.empty()) << "no window; the command said:\n" << query_said();
  EXPECT_NE(title.find("Axle"), std::string::npos) << title;
  EXPECT_EQ(xdotool({"getwindowname", window}), title);
  // Give gnuplot a moment to draw after mapping the window, then look.
  std::this_thread::sleep_for(std::chrono::seconds(1));
  const viewer::ScreenImage screen = xvfb.ReadScreen();
  size_t light = 0, coloured = 0;
  std::set<uint32_t> colours;
  for (const uint32_t p : screen.pixels) {
    const int r = p >> 16 & 0xff, g = p >> 8 & 0xff, b = p & 0xff;
    colours.insert(p);
    if (r > 200 && g > 200 && b > 200) ++light;
    // Text, axes and the page are grey; a curve has a hue.
    if (std::max({r, g, b}) - std::min({r, g, b}) > 80) ++coloured;
  }
  // The root window is black: the window's light page covers much of the
  // 1024x768 screen (900x540 asked), and the curve is a few hundred pixels.
  EXPECT_GT(light, 900u * 540u / 2) << colours.size() << " colours";
  EXPECT_GT(coloured, 300u) << colours.size() << " colours";
  EXPECT_TRUE(query.running()) << "the command ended with its window open:\n" << query_said();
  EXPECT_FALSE(ProcessesOnDisplay("gnuplot", xvfb.display()).empty());

  // No window manager: focus the window directly, then press q in it.
  xdotool({"windowfocus", window});
  xdotool({"key", "q"});
  EXPECT_EQ(query.Wait(std::chrono::seconds(10)).value_or(-1), 0) << query_said();
  EXPECT_EQ(ProcessesOnDisplay("gnuplot", xvfb.display()), std::vector<pid_t>{});
  EXPECT_EQ(xdotool({"search", "--name", "rate of joint Axle"}, 1), "");
}

// The program: a PNG from the command line, errors on standard error.
TEST_F(QueryToolTest, ProgramPlotsAndRefuses) {
  Log(SpinRun(500, 41));
  const std::string png = (dir_ / "wheel.png").string();
  std::string output;
  EXPECT_EQ(RunQuery({"plot", "angle", "last", "--joint", "Axle", "-o", png, "--db-options",
                      server_->reader_options()},
                     &output),
            0)
      << output;
  uintmax_t size = 0;
  EXPECT_TRUE(IsPng(png, &size)) << output;
  EXPECT_GT(size, 10000u);
  EXPECT_EQ(RunQuery({"names", "last", "--db-options", server_->reader_options()}, &output), 0)
      << output;
  EXPECT_NE(output.find("joints: Shoulder (HINGE) Axle (HINGE)"), std::string::npos) << output;
  EXPECT_NE(output.find(" Wheel ("), std::string::npos) << output;
  // No -o and a display where no X server answers: an error naming gnuplot
  // and the display (or, with gnuplot-nox, that it has no window
  // terminal), not a hang.
  ::setenv("DISPLAY", ":97", 1);
  EXPECT_EQ(RunQuery({"plot", "rate", "last", "--joint", "Axle", "--db-options",
                      server_->reader_options()},
                     &output),
            1);
  ::unsetenv("DISPLAY");
  EXPECT_NE(output.find("gnuplot"), std::string::npos) << output;
  EXPECT_EQ(RunQuery({"plot", "angle", "last", "--joint", "Axel", "-o", png, "--db-options",
                      server_->reader_options()},
                     &output),
            1);
  EXPECT_NE(output.find("did you mean 'Axle'"), std::string::npos) << output;
  EXPECT_EQ(RunQuery({"joints", "last", "--joint", "Axle", "--every", "0", "--db-options",
                      server_->reader_options()},
                     &output),
            1);
  EXPECT_NE(output.find("--every 0: must be 1 or more"), std::string::npos) << output;
  EXPECT_EQ(RunQuery({"delete", "1", "--db-options", server_->reader_options()}, &output), 1);
  EXPECT_NE(output.find("deleting needs an administrator"), std::string::npos) << output;
  EXPECT_EQ(RunQuery({"delete", "1", "--db-options", server_->admin_options()}, &output), 0) << output;
  EXPECT_NE(output.find("deleted 1 simulation(s) (1) with 500 logged steps"), std::string::npos) << output;
}

}  // namespace
}  // namespace simpartner::logger
