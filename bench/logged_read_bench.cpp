// How fast a logged run comes back out of the database: a gen3
// run on flat ground (26 bodies, 25 joints at every 1 ms step; straight on,
// then in a left turn) is logged by the logger's writer into a private
// MariaDB server, then read
//   1. by the query library's arrays (what Python's read_logged uses):
//      the whole run, a time range, one body;
//   2. by Python's simpartner.read_logged (when the module is built);
//   3. by the row-by-row export (simpartner-query poses, joints, forces:
//      what read_logged and the wheel-forces plot read before);
//   4. as plots: wheel-forces and track (MakePlot, then gnuplot's PNG).
// Each figure is the wall time (the best of three for 1 and 2), the
// multiple of real time (sim seconds read per second), and the CPU time of
// the reader and of the server.
//   bench/logged_read_bench [--seconds S] [--datadir DIR]
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cpu_time.h"
#include "simpartner/command_line.h"
#include "simpartner/child_process.h"
#include "simpartner/command_t.hpp"
#include "simpartner/logger/private_server.h"
#include "simpartner/logger/query.h"
#include "simpartner/logger/writer.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/simulation.h"

namespace {

using namespace simpartner;
using namespace simpartner::logger;
using Clock = std::chrono::steady_clock;
using bench::CpuSeconds;
using bench::ServerCpuSeconds;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

template <class Message>
Record Encode(RecordKind kind, int64_t simulation_id, const Message& message) {
  Record r;
  r.kind = kind;
  r.simulation_id = simulation_id;
  r.received_us = 1;
  r.payload.resize(static_cast<size_t>(message.getEncodedSize()));
  message.encode(r.payload.data(), 0, static_cast<int>(r.payload.size()));
  return r;
}

command_t Command(const std::string& target, std::vector<double> values) {
  command_t c{};
  c.request_id = 1;
  c.sender = "logged_read_bench";
  c.target = target;
  c.action = command_t::ACTION_SET;
  c.apply_at_step = -1;
  c.values = std::move(values);
  c.num_values = static_cast<int32_t>(c.values.size());
  return c;
}

// Drives gen3: straight ahead for the first third, then in a left turn
// (the Turner at 0.3 rad, the outer wheels faster), as
// examples/drive_and_plot.py does.
void Drive(sim::Simulation* sim, bool turning) {
  std::vector<command_t> commands;
  if (turning) commands.push_back(Command("TurnerMotor", {1000, 0.3, 100, 100, 0}));
  for (int w = 1; w <= 4; ++w)
    commands.push_back(Command("Axle" + std::to_string(w) + "Motor",
                               {1000, turning && (w == 2 || w == 3) ? 3.6 : 4.4}));
  for (const command_t& c : commands)
    if (const auto refused = sim->Submit(c); refused && !refused->accepted)
      throw Error("the sim refused " + c.target + ": " + refused->reason);
}

// Logs `steps` steps of gen3 driving on flat ground, a thousand steps per
// write (the records of the whole run would not fit in memory).
void LogGen3Run(const PrivateServer& server, int64_t steps) {
  model::WorldLoadResult loaded =
      model::LoadWorldFile(std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml");
  if (!loaded.world) throw Error(loaded.diagnostics.Format());
  const int64_t simulation_id = 7001;
  sim::Simulation sim(*loaded.world, Parameters(), simulation_id);
  WriterOptions options;
  options.lcm_url = "bench";
  options.scratch_dir = server.dir();
  DbWriter writer(server.LoggerTarget("simpartner"), options, [](const std::string&) {});
  model_t model;
  sim.FillModel(&model);
  model.host = "bench";
  writer.Write({Encode(RecordKind::kModel, simulation_id, model)});
  std::vector<Record> batch;
  for (int64_t i = 0; i < steps; ++i) {
    if (i == 0 || i == steps / 3) Drive(&sim, i > 0);
    sim.Step();
    state_t state;
    sim.FillState(&state);
    batch.push_back(Encode(RecordKind::kState, simulation_id, state));
    if (batch.size() == 1000 || i + 1 == steps) {
      writer.Write(batch);
      batch.clear();
    }
  }
  writer.Write({MakeEndedRecord(simulation_id, 2, EndedPayload{steps, EndKind::kStopped, ""})});
}

std::unique_ptr<DbConnection> Reader(const PrivateServer& server) {
  DbTarget target = server.LoggerTarget("simpartner");
  target.option_file = server.reader_options();
  std::unique_ptr<DbConnection> db = DbConnection::Open(target, false);
  db->UseDatabase(false);
  return db;
}

// Wall time and CPU time (of this process and of the server) of a read.
class Timer {
 public:
  explicit Timer(const PrivateServer& server)
      : server_(server), cpu_(CpuSeconds()), server_cpu_(ServerCpuSeconds(server)) {}
  double Wall() const { return SecondsSince(start_); }
  std::string Cpu() const {
    char text[96];
    std::snprintf(text, sizeof text, "CPU %.2f s here + %.2f s server", CpuSeconds() - cpu_,
                  ServerCpuSeconds(server_) - server_cpu_);
    return text;
  }

 private:
  const PrivateServer& server_;
  Clock::time_point start_ = Clock::now();
  double cpu_, server_cpu_;
};

void Report(const char* what, double seconds, double sim_seconds, const std::string& detail) {
  std::printf("  %-44s %7.2f s  %7.1f x real time  %s\n", what, seconds, sim_seconds / seconds,
              detail.c_str());
}

constexpr int kRepeats = 3;

// 1. The query library's arrays: the whole run, its middle third, one body.
void Arrays(const PrivateServer& server, double sim_seconds) {
  std::unique_ptr<DbConnection> db = Reader(server);
  struct Case {
    const char* what;
    LoggedRunRequest request;
    double span;
  };
  LoggedRunRequest whole;
  LoggedRunRequest third = whole;
  third.from = sim_seconds / 3;
  third.to = 2 * sim_seconds / 3;
  LoggedRunRequest wheel = whole;
  wheel.bodies = {false, {"Wheel1"}};
  wheel.joints = {false, {}};
  for (const Case& c : {Case{"arrays, the whole run", whole, sim_seconds},
                        Case{"arrays, the middle third (--from, --to)", third, sim_seconds / 3},
                        Case{"arrays, one body (Wheel1), no joints", wheel, sim_seconds}}) {
    // The best of kRepeats: what the reading costs, not what the other
    // programs on the machine took meanwhile.
    double best = 1e9;
    std::string detail;
    for (int i = 0; i < kRepeats; ++i) {
      const Timer timer(server);
      const LoggedRun run = ReadLoggedRun(db.get(), c.request);
      if (timer.Wall() >= best) continue;
      best = timer.Wall();
      detail = std::to_string(run.time.size()) + " steps, " + std::to_string(run.poses.size()) +
               " bodies, " + std::to_string(run.joints.size()) + " joints; " + timer.Cpu();
    }
    Report(c.what, best, c.span, detail);
  }
}

// 3. The row-by-row export: poses and joints (what read_logged did before
// it read arrays), and the forces of every body (what the wheel-forces
// plot read before it read the wheels' arrays).
void RowByRow(const PrivateServer& server, double sim_seconds) {
  std::unique_ptr<DbConnection> db = Reader(server);
  ExportRequest poses, joints, forces;
  joints.kind = ExportKind::kJoints;
  joints.unwrap = true;
  forces.kind = ExportKind::kForces;
  struct Case {
    const char* what;
    std::vector<ExportRequest> requests;
  };
  for (const Case& c : {Case{"row-by-row export, poses + joints", {poses, joints}},
                        Case{"row-by-row export, forces of every body", {forces}}}) {
    size_t rows = 0;
    const Timer timer(server);
    for (const ExportRequest& request : c.requests)
      ReadExport(db.get(), request, [&](const ExportStep& step) { rows += step.rows.size(); });
    Report(c.what, timer.Wall(), sim_seconds, std::to_string(rows) + " rows; " + timer.Cpu());
  }
}

// 2. Python's read_logged in a python3 of its own, timed inside it: the
// whole run by its id, the middle third, one body.
void Python(const PrivateServer& server, double sim_seconds) {
  const std::string module_dir = std::string(SP_BINARY_DIR) + "/python";
  if (std::string(SP_PYTHON_EXECUTABLE).empty()) {
    std::cout << "  (the Python module is not built in " << module_dir << ")\n";
    return;
  }
  const std::string log = server.dir() + "/python.log";
  ::setenv("PYTHONPATH", module_dir.c_str(), 1);
  const std::string script =
      "import sys, time, simpartner\n"
      "options, first, last = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])\n"
      "def timed(what, simulation='last', **kw):\n"
      "    s = 1e9\n"
      "    for _ in range(3):\n"
      "        t, c = time.perf_counter(), time.process_time()\n"
      "        run = simpartner.read_logged(simulation, db_options=options, **kw)\n"
      "        if time.perf_counter() - t < s:\n"
      "            s, cpu = time.perf_counter() - t, time.process_time() - c\n"
      "    span = run['time'][-1] - run['time'][0] + 0.001\n"
      "    print('  %-44s %7.2f s  %7.1f x real time  %d steps, %d bodies, %d joints; CPU %.2f s' "
      "% (\n"
      "        what, s, span / s, len(run['time']), len(run['bodies']), len(run['joints']), cpu))\n"
      "    return run\n"
      "sim = simpartner.read_logged(db_options=options, bodies=[], joints=[])['simulation']\n"
      "timed('Python read_logged(%d), the whole run' % sim, sim)\n"
      "timed('Python read_logged, start=%g, end=%g' % (first, last), start=first, end=last)\n"
      "timed('Python read_logged, bodies=\"Wheel1\", joints=[]', bodies='Wheel1', joints=[])\n";
  ChildProcess python({SP_PYTHON_EXECUTABLE, "-c", script, server.reader_options(),
                       std::to_string(sim_seconds / 3), std::to_string(2 * sim_seconds / 3)},
                      log);
  const int status = python.Wait(std::chrono::minutes(10)).value_or(-1);
  std::ifstream in(log);
  std::cout << in.rdbuf();
  if (status != 0)
    std::cout << "  (" SP_PYTHON_EXECUTABLE " ended with status " << status
              << (status == -1 ? ", still running after 10 minutes" : "") << ")\n";
}

// 4. The wheel-force and track plots, drawn into PNGs in the server's directory.
void Plots(const PrivateServer& server, double sim_seconds) {
  std::unique_ptr<DbConnection> db = Reader(server);
  for (const PlotKind kind : {PlotKind::kWheelForces, PlotKind::kTrack}) {
    PlotRequest request;
    request.kind = kind;
    const Timer timer(server);
    const Plot plot = MakePlot(db.get(), request);
    const double read = timer.Wall();
    const std::string png =
        server.dir() + (kind == PlotKind::kTrack ? "/track.png" : "/wheel-forces.png");
    DrawPlotPng(plot, png);
    Report(
        kind == PlotKind::kTrack ? "plot track (read + draw)" : "plot wheel-forces (read + draw)",
        timer.Wall(), sim_seconds,
        std::to_string(plot.series.size()) + " series, read " +
            std::to_string(static_cast<int>(read * 1000)) + " ms; " + timer.Cpu());
  }
}

// Logs the run into the server, or with `reuse` takes the one logged
// there before; returns its sim time [s].
double LogOrReuseRun(const PrivateServer& server, double seconds, bool reuse) {
  const std::string marker = server.dir() + "/logged";
  int64_t steps = static_cast<int64_t>(seconds * 1000 + 0.5);
  if (reuse) {
    std::ifstream(marker) >> steps;
    std::cout << "reusing the run of " << steps << " steps logged before\n";
  } else {
    const auto start = Clock::now();
    LogGen3Run(server, steps);
    std::ofstream(marker) << steps << "\n";
    std::printf("logged %lld steps of gen3 (%.0f s of sim time) in %.1f s\n",
                static_cast<long long>(steps), seconds, SecondsSince(start));
  }
  return static_cast<double>(steps) / 1000;
}

void ReadBack(const PrivateServer& server, double sim_seconds) {
  std::ifstream loadavg("/proc/loadavg");
  std::string load;
  loadavg >> load;
  std::cout << "\n== reading the run back (best of " << kRepeats
            << " for the arrays and Python; load average " << load << ")\n";
  Arrays(server, sim_seconds);
  Python(server, sim_seconds);
  RowByRow(server, sim_seconds);
  Plots(server, sim_seconds);
}

}  // namespace

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "logged_read_bench";
  spec.summary =
      "How fast a logged gen3 run (26 bodies, 25 joints, every 1 ms step) is read back from a\n"
      "private MariaDB server: the query library's arrays, Python's read_logged, the\n"
      "row-by-row export and the wheel-forces and track plots; wall time, multiple of real\n"
      "time and CPU time.";
  spec.options = {
      simpartner::Number("seconds", "S", "sim time of the logged run (default 65)"),
      simpartner::Text("datadir", "DIR",
                       "keep the server (and the PNGs) in DIR and reuse its run next time "
                       "(default: a temporary one, removed)"),
  };
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  try {
    const bool keep = args.Has("datadir");
    char dir_template[] = "/tmp/sp_read_bench.XXXXXX";
    const std::string top = keep ? "" : ::mkdtemp(dir_template);
    const std::string dir = keep ? args.Text("datadir", "") : top + "/db";
    const bool reuse = keep && std::filesystem::exists(dir + "/logged");
    PrivateServer server(std::string(SP_SOURCE_DIR) + "/scripts/mariadb", dir, !keep);
    server.Start();
    std::cout << "private MariaDB server in " << server.dir() << "\n";
    ReadBack(server, LogOrReuseRun(server, args.Number("seconds", 65), reuse));
    if (keep) std::cout << "PNGs in " << server.dir() << "\n";
    server.Stop();
    if (!keep) std::filesystem::remove_all(top);
  } catch (const std::exception& e) {
    std::cerr << "logged_read_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
