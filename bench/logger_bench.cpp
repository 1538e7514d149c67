// Figures of the database logger, each on a private MariaDB
// server started for the run in a temporary directory:
//   1. insert methods on a 9-column Pose-like table: one INSERT per row
//      (what the original did), multi-row INSERTs of 1000 rows in
//      transactions, LOAD DATA LOCAL: rows/s
//   2. the logger's writer alone on real gen3 states (SimulationRow, Pose,
//      ForceAndTorque, JointPose: 78 rows a step), per batch size and
//      method: steps/s and the multiple of real time it could take
//   3. end to end beside a running simpartner-sim (gen3, flat ground): the
//      sim alone, then sim + logger, then sim + lcm-logger to a file, at
//      real time: loss, lag from publish to commit (p50/p99), the sim's
//      steps/s and step cost with and without the logger
//   4. the highest multiple of real time the logger keeps up with (no
//      loss, no spilling, lag bounded)
//   5. bytes per logged step per table, plain and with InnoDB page
//      compression, and what compression costs the writer
//   bench/logger_bench [--seconds S] [--skip 1,2,3,4,5] [--server-sql STATEMENT ...]
// (--server-sql runs a statement as the server's administrator first, e.g.
// 'SET GLOBAL innodb_adaptive_hash_index = 0', for tuning experiments)
#include <lcm/lcm-cpp.hpp>
#include <signal.h>
#include <sys/eventfd.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_line.h"
#include "simpartner/logger/logger.h"
#include "simpartner/logger/private_server.h"
#include "simpartner/logger/query.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/logger/writer.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/simulation.h"
#include "simpartner/status_t.hpp"
#include "cpu_time.h"

namespace {

using namespace simpartner;
using namespace simpartner::logger;
using Clock = std::chrono::steady_clock;
using bench::CpuSeconds;
using bench::ServerCpuSeconds;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

std::string Gen3World() { return std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml"; }

// ---- 1. insert methods -------------------------------------------------

void CreateBenchTable(DbConnection* db) {
  db->Execute("DROP TABLE IF EXISTS BenchPose", "DROP TABLE BenchPose");
  db->Execute("CREATE TABLE BenchPose (simulationRowID BIGINT UNSIGNED NOT NULL, bodyID INT "
              "UNSIGNED NOT NULL, x DOUBLE NOT NULL, y DOUBLE NOT NULL, z DOUBLE NOT NULL, axisX "
              "DOUBLE NOT NULL, axisY DOUBLE NOT NULL, axisZ DOUBLE NOT NULL, angle DOUBLE NOT "
              "NULL, PRIMARY KEY (simulationRowID, bodyID)) ENGINE=InnoDB",
              "CREATE TABLE BenchPose");
}

void AppendRowValues(std::string* out, int64_t row, std::mt19937_64* rng, char sep) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  AppendInt(out, row / 26);
  out->push_back(sep);
  AppendInt(out, row % 26);
  for (int k = 0; k < 7; ++k) {
    out->push_back(sep);
    AppendDouble(out, u(*rng));
  }
}

void InsertMethods(const PrivateServer& server) {
  std::cout << "\n== 1. insert methods, 9-column Pose-like table (primary key only)\n";
  DbTarget target = server.AdminTarget("simpartner_bench");
  std::unique_ptr<DbConnection> db = DbConnection::Open(target, true);
  db->UseDatabase(true);
  std::mt19937_64 rng(1);
  const char* header = "INSERT INTO BenchPose VALUES ";

  CreateBenchTable(db.get());
  const int single_rows = 20000;
  auto start = Clock::now();
  for (int64_t r = 0; r < single_rows; ++r) {
    std::string sql = std::string(header) + "(";
    AppendRowValues(&sql, r, &rng, ',');
    sql += ")";
    db->Execute(sql, "INSERT");  // autocommit: one round trip and commit per row
  }
  const double single = single_rows / Seconds(Clock::now() - start);
  std::printf("  one INSERT per row (autocommit)        %9.0f rows/s  (%d rows)\n", single, single_rows);

  CreateBenchTable(db.get());
  const int rows = 500000;
  start = Clock::now();
  for (int64_t r = 0; r < rows;) {
    db->Begin();
    for (int statement = 0; statement < 10 && r < rows; ++statement) {
      std::string sql = header;
      for (int k = 0; k < 1000 && r < rows; ++k, ++r) {
        if (k > 0) sql.push_back(',');
        sql.push_back('(');
        AppendRowValues(&sql, r, &rng, ',');
        sql.push_back(')');
      }
      db->Execute(sql, "INSERT");
    }
    db->Commit();
  }
  const double multi = rows / Seconds(Clock::now() - start);
  std::printf("  multi-row INSERT, 1000 rows/statement  %9.0f rows/s  (%d rows, 10 statements per transaction)\n",
              multi, rows);

  CreateBenchTable(db.get());
  const std::string file = server.dir() + "/bench.tsv";
  start = Clock::now();
  for (int64_t r = 0; r < rows;) {
    std::string data;
    for (int k = 0; k < 10000 && r < rows; ++k, ++r) {
      AppendRowValues(&data, r, &rng, '\t');
      data.push_back('\n');
    }
    std::ofstream(file, std::ios::binary) << data;
    db->Execute("LOAD DATA LOCAL INFILE " + Quoted(file) + " INTO TABLE BenchPose", "LOAD DATA");
  }
  const double load = rows / Seconds(Clock::now() - start);
  std::printf("  LOAD DATA LOCAL, 10000 rows/file       %9.0f rows/s  (%d rows)\n", load, rows);
  db->Execute("DROP TABLE BenchPose", "DROP TABLE BenchPose");
}

// ---- 2. the writer on gen3 states ----------------------------------------

std::vector<Record> Gen3Records(int steps, int64_t simulation_id) {
  model::WorldLoadResult loaded = model::LoadWorldFile(Gen3World());
  if (!loaded.world) throw Error(loaded.diagnostics.Format());
  Parameters params;
  sim::Simulation sim(*loaded.world, params, simulation_id);
  std::vector<Record> records;
  auto add = [&](RecordKind kind, const auto& message) {
    Record r;
    r.kind = kind;
    r.simulation_id = simulation_id;
    r.payload.resize(static_cast<size_t>(message.getEncodedSize()));
    message.encode(r.payload.data(), 0, static_cast<int>(r.payload.size()));
    records.push_back(std::move(r));
  };
  model_t model;
  sim.FillModel(&model);
  model.host = "bench";
  add(RecordKind::kModel, model);
  for (int i = 0; i < steps; ++i) {
    sim.Step();
    state_t state;
    sim.FillState(&state);
    add(RecordKind::kState, state);
  }
  return records;
}

void WriterThroughput(const PrivateServer& server) {
  std::cout << "\n== 2. the logger's writer alone, gen3 states (78 rows a step), no sim running\n";
  const int steps = 6000;
  int run = 0;
  for (InsertMethod method : {InsertMethod::kMultiRowInsert, InsertMethod::kLoadDataLocal}) {
    for (size_t batch : {10, 25, 50, 100, 1000}) {
      const std::vector<Record> records = Gen3Records(steps, 1000 + run);
      const std::string database = "simpartner_w" + std::to_string(run++);
      WriterOptions options;
      options.method = method;
      options.lcm_url = "bench";
      options.scratch_dir = server.dir();
      DbWriter writer(server.LoggerTarget(database), options, [](const std::string&) {});
      writer.Write({records[0]});  // the model
      uint64_t rows = 0;
      const double cpu_start = CpuSeconds();
      const double server_start = ServerCpuSeconds(server);
      const auto start = Clock::now();
      for (size_t i = 1; i < records.size(); i += batch) {
        const std::vector<Record> part(records.begin() + static_cast<std::ptrdiff_t>(i),
                                       records.begin() + static_cast<std::ptrdiff_t>(std::min(records.size(), i + batch)));
        rows += writer.Write(part).rows_written;
      }
      const double s = Seconds(Clock::now() - start);
      const double cpu = CpuSeconds() - cpu_start;
      const double server_cpu = ServerCpuSeconds(server) - server_start;
      std::printf("  %-17s %4zu steps/transaction  %7.0f steps/s  %8.0f rows/s  = %.2f x real time (1 kHz); "
                  "CPU per step: writer %.0f us, server %.0f us\n",
                  InsertMethodName(method), batch, steps / s, rows / s, steps / s / 1000.0,
                  1e6 * cpu / steps, 1e6 * server_cpu / steps);
    }
  }
}

// ---- 3 and 4. beside a running sim ------------------------------------------

// What a run of the sim looked like from its SIM_STATUS messages.
struct SimFigures {
  double wall_s = 0;
  int64_t steps = 0;
  double steps_per_s = 0;
  double step_cost_us = 0;  // mean of the status reports while running
  int exit_status = -1;
};

class StatusListener {
 public:
  explicit StatusListener(const std::string& url) : lcm_(url) {
    lcm_.subscribe(channels::kStatus, &StatusListener::OnStatus, this)->setQueueCapacity(1000);
    thread_ = std::thread([this] {
      while (!stop_) lcm_.handleTimeout(50);
    });
  }
  ~StatusListener() {
    stop_ = true;
    thread_.join();
  }
  double MeanStepCostUs() {
    std::lock_guard<std::mutex> lock(mutex_);
    return costs_ == 0 ? 0.0 : 1e6 * cost_sum_ / costs_;
  }

 private:
  void OnStatus(const lcm::ReceiveBuffer*, const std::string&, const status_t* s) {
    if (s->run_state != status_t::RUN_RUNNING || s->step_cost <= 0) return;
    std::lock_guard<std::mutex> lock(mutex_);
    cost_sum_ += s->step_cost;
    ++costs_;
  }
  lcm::LCM lcm_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::mutex mutex_;
  double cost_sum_ = 0;
  int costs_ = 0;
};

SimFigures RunSim(const std::string& url, double speed, double sim_seconds, const std::string& log) {
  StatusListener status(url);
  SimFigures f;
  const auto start = Clock::now();
  char speed_text[32], duration_text[32];
  std::snprintf(speed_text, sizeof speed_text, "--speed=%g", speed);
  std::snprintf(duration_text, sizeof duration_text, "--duration=%g", sim_seconds);
  ChildProcess sim({std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim", "--params", "/dev/null",
                    "--environment=" + Gen3World(), "--lcm-url", url, speed_text, duration_text},
                   log);
  f.exit_status = sim.Wait(std::chrono::seconds(static_cast<int>(sim_seconds / std::max(speed, 0.05)) + 600))
                      .value_or(-1);
  f.wall_s = Seconds(Clock::now() - start);
  f.steps = static_cast<int64_t>(std::llround(sim_seconds / 0.001));
  f.steps_per_s = f.steps / f.wall_s;
  f.step_cost_us = status.MeanStepCostUs();
  return f;
}

struct LoggedRun {
  SimFigures sim;
  double logger_cpu = 0;  // [cores] while the sim ran and the logger drained
  double server_cpu = 0;
  LoggerStats logger;
  int64_t rows_in_db = 0;
  double drain_s = 0;  // after the sim ended, until the last step was committed
  int64_t peak_queue_bytes = 0;
};

LoggedRun RunWithLogger(const PrivateServer& server, const std::string& url, const std::string& database,
                        double speed, double sim_seconds, const std::string& dir) {
  LoggerOptions options;
  options.lcm_url = url;
  options.db = server.LoggerTarget(database);
  options.spool_dir = dir + "/spool-" + database;
  options.status_period = 3600;
  options.sender = "logger_bench";
  std::ostringstream out;
  Reporter reporter(&out, "logger");
  Logger logger(options, &reporter);
  const int stop_fd = ::eventfd(0, EFD_CLOEXEC);
  int status = -1;
  std::thread thread([&] { status = logger.Run(stop_fd); });
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  LoggedRun run;
  const double cpu_start = CpuSeconds();
  const double server_start = ServerCpuSeconds(server);
  const auto start = Clock::now();
  run.sim = RunSim(url, speed, sim_seconds, dir + "/sim-" + database + ".log");
  const auto ended = Clock::now();
  while (logger.Stats().states_written < static_cast<uint64_t>(run.sim.steps) &&
         Clock::now() - ended < std::chrono::seconds(600))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  run.drain_s = Seconds(Clock::now() - ended);
  const double wall = Seconds(Clock::now() - start);
  run.logger_cpu = (CpuSeconds() - cpu_start) / wall;
  run.server_cpu = (ServerCpuSeconds(server) - server_start) / wall;
  const uint64_t one = 1;
  if (::write(stop_fd, &one, sizeof one) != sizeof one) throw Error("eventfd write failed");
  thread.join();
  ::close(stop_fd);
  run.logger = logger.Stats();
  run.peak_queue_bytes = static_cast<int64_t>(run.logger.queue.peak_memory_bytes);
  std::unique_ptr<DbConnection> db = DbConnection::Open(server.AdminTarget(database), false);
  db->UseDatabase(false);
  run.rows_in_db = db->QueryInt("SELECT COUNT(*) FROM SimulationRow", "count", -1);
  if (status != 0) std::cout << "  (logger exit status " << status << ")\n" << out.str();
  return run;
}

std::string UniqueUrl(int offset) {
  const int port = 30000 + (static_cast<int>(::getpid()) * 11 + offset) % 10000;
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
}

void PrintLogged(const char* label, const LoggedRun& r) {
  const LoggerStats& s = r.logger;
  std::printf("  %-26s sim %6.0f steps/s, step cost %4.0f us; logged %lld of %lld steps (%lld missing), "
              "%llu rows; lag p50 %.1f ms p99 %.1f ms max %.1f ms; drain %.2f s; peak queue %.1f MB, "
              "spilled %llu records; CPU: logger %.2f, server %.2f cores\n",
              label, r.sim.steps_per_s, r.sim.step_cost_us, static_cast<long long>(r.rows_in_db),
              static_cast<long long>(r.sim.steps), static_cast<long long>(r.sim.steps - r.rows_in_db),
              static_cast<unsigned long long>(s.rows_written), s.lag.Percentile(0.5) / 1000,
              s.lag.Percentile(0.99) / 1000, static_cast<double>(s.lag.max()) / 1000, r.drain_s,
              static_cast<double>(r.peak_queue_bytes) / 1e6,
              static_cast<unsigned long long>(s.queue.spilled_records), r.logger_cpu, r.server_cpu);
}

void BesideTheSim(const PrivateServer& server, double seconds, const std::string& dir) {
  std::cout << "\n== 3. gen3 at real time for " << seconds << " s beside simpartner-sim (one machine)\n";
  const std::string url = UniqueUrl(0);
  const SimFigures alone = RunSim(url, 1.0, seconds, dir + "/sim-alone.log");
  std::printf("  %-26s sim %6.0f steps/s, step cost %4.0f us\n", "sim alone", alone.steps_per_s,
              alone.step_cost_us);
  const LoggedRun logged = RunWithLogger(server, url, "simpartner_rt", 1.0, seconds, dir);
  PrintLogged("sim + simpartner-logger", logged);

  // lcm-logger to a file: the floor (no database at all).
  const std::string file = dir + "/run.lcmlog";
  SimFigures with_lcm_logger;
  {
    ChildProcess recorder({"/usr/bin/lcm-logger", "--lcm-url=" + WithReceiveBuffer(url), "--quiet", file},
                          dir + "/lcm-logger.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    with_lcm_logger = RunSim(url, 1.0, seconds, dir + "/sim-lcm-logger.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    recorder.Signal(SIGINT);
    recorder.Wait(std::chrono::seconds(10));
  }
  lcm::LogFile log(file, "r");
  int64_t states = 0;
  while (const lcm::LogEvent* event = log.readNextEvent())
    if (event->channel == channels::kState) ++states;
  std::printf("  %-26s sim %6.0f steps/s, step cost %4.0f us; recorded %lld of %lld steps, %.1f MB\n",
              "sim + lcm-logger (file)", with_lcm_logger.steps_per_s, with_lcm_logger.step_cost_us,
              static_cast<long long>(states), static_cast<long long>(with_lcm_logger.steps),
              static_cast<double>(std::filesystem::file_size(file)) / 1e6);
  std::printf("  sim step cost with / without the logger: %.3f (steps/s ratio %.3f)\n",
              alone.step_cost_us / std::max(1.0, logged.sim.step_cost_us),
              logged.sim.steps_per_s / alone.steps_per_s);

  std::cout << "\n   as fast as possible (speed 0), " << seconds << " s of sim time:\n";
  const SimFigures fast_alone = RunSim(url, 0.0, seconds, dir + "/sim-fast.log");
  std::printf("  %-26s sim %6.0f steps/s\n", "sim alone", fast_alone.steps_per_s);
  const LoggedRun fast = RunWithLogger(server, url, "simpartner_fast", 0.0, seconds, dir);
  PrintLogged("sim + simpartner-logger", fast);
  std::printf("  sim steps/s with / without the logger: %.3f\n", fast.sim.steps_per_s / fast_alone.steps_per_s);
}

void HighestMultiple(const PrivateServer& server, double seconds, const std::string& dir) {
  std::cout << "\n== 4. multiples of real time, " << seconds << " s of wall time each: kept up = every "
               "step, nothing spilled, p99 lag under 1 s\n";
  double best = 0;
  int n = 0;
  for (double speed : {1.0, 1.25, 1.5, 2.0, 3.0}) {
    const LoggedRun r = RunWithLogger(server, UniqueUrl(1), "simpartner_x" + std::to_string(n++), speed,
                                      seconds * speed, dir);
    char label[64];
    std::snprintf(label, sizeof label, "speed %.2f", speed);
    PrintLogged(label, r);
    const bool kept_up = r.rows_in_db == r.sim.steps && r.logger.queue.spilled_records == 0 &&
                         r.logger.lag.Percentile(0.99) < 1e6;
    if (!kept_up) break;
    best = std::max(best, r.sim.steps_per_s / 1000.0);
  }
  std::printf("  highest multiple of real time kept up with: %.2f\n", best);
}

}  // namespace

// ---- 5. storage per logged step ------------------------------------------

// The same gen3 states written by the logger's writer into plain tables and
// into tables with InnoDB page compression (simpartner-query compress on):
// bytes per step per table as InnoDB counts pages and as allocated on disk,
// an hour at 1 kHz, and what compression costs the writer.
void StoragePerStep(const PrivateServer& server, double seconds) {
  const int steps = static_cast<int>(seconds * 1000);
  std::cout << "\n== 5. storage per logged step, gen3 at every step (" << steps
            << " steps at 1 ms), plain and InnoDB page-compressed (zlib)\n";
  const std::vector<Record> records = Gen3Records(steps, 5000);
  const size_t batch = 100;
  for (const bool compressed : {false, true}) {
    const std::string database = compressed ? "simpartner_compressed" : "simpartner_plain";
    WriterOptions options;
    options.lcm_url = "bench";
    options.scratch_dir = server.dir();
    DbWriter writer(server.LoggerTarget(database), options, [](const std::string&) {});
    writer.Write({records[0]});  // the model; creates the tables
    std::unique_ptr<DbConnection> admin = DbConnection::Open(server.AdminTarget(database), false);
    admin->UseDatabase(false);
    if (compressed) SetPageCompression(admin.get(), true);
    uint64_t rows = 0;
    const double cpu_start = CpuSeconds();
    const double server_start = ServerCpuSeconds(server);
    const auto start = Clock::now();
    for (size_t i = 1; i < records.size(); i += batch) {
      const std::vector<Record> part(
          records.begin() + static_cast<std::ptrdiff_t>(i),
          records.begin() + static_cast<std::ptrdiff_t>(std::min(records.size(), i + batch)));
      rows += writer.Write(part).rows_written;
    }
    const double s = Seconds(Clock::now() - start);
    const double cpu = CpuSeconds() - cpu_start;
    const double server_cpu = ServerCpuSeconds(server) - server_start;
    std::printf("  %s: writer %.0f steps/s, %.0f rows/s (%.1f x real time); CPU per step: "
                "writer %.0f us, server %.0f us\n",
                compressed ? "page-compressed" : "plain", steps / s, rows / s, steps / s / 1000.0,
                1e6 * cpu / steps, 1e6 * server_cpu / steps);
    std::printf("    %-16s %12s %14s %14s\n", "table", "rows/step", "bytes/step", "on disk/step");
    double logical = 0, disk = 0;
    for (const TableStorage& t : ReadTableStorage(admin.get())) {
      std::printf("    %-16s %12.1f %14.0f %14.0f\n", t.table.c_str(),
                  static_cast<double>(t.rows) / steps, static_cast<double>(t.logical_bytes) / steps,
                  static_cast<double>(t.disk_bytes) / steps);
      logical += static_cast<double>(t.logical_bytes) / steps;
      disk += static_cast<double>(t.disk_bytes) / steps;
    }
    std::printf("    %-16s %12s %14.0f %14.0f  -> one hour at 1 kHz: %.1f GB on disk\n", "all", "",
                logical, disk, disk * 3.6e6 / 1e9);
  }
}

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "logger_bench";
  spec.summary =
      "Figures of the database logger on a private MariaDB server in a temporary directory:\n"
      "  1. insert methods (row by row, multi-row, LOAD DATA): rows/s\n"
      "  2. the writer alone on real gen3 states: steps/s per batch size and method\n"
      "  3. end to end beside a running simpartner-sim at real time: loss, lag, sim cost\n"
      "  4. the highest multiple of real time the logger keeps up with\n"
      "  5. bytes per logged step per table, plain and page-compressed, and the writer's cost";
  spec.options = {
      simpartner::Number("seconds", "S", "sim time of parts 3, 4 and 5 (default 20)"),
      simpartner::Text("skip", "LIST", "parts to leave out, e.g. 1,2"),
      simpartner::Text("server-sql", "STATEMENT",
                       "run as the server's administrator first (repeatable), e.g.\n"
                       "'SET GLOBAL innodb_adaptive_hash_index = 0'"),
  };
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const double seconds = args.Number("seconds", 20);
  const std::vector<std::string> server_sql = args.All("server-sql");
  std::set<int> skip;
  {
    std::stringstream list(args.Text("skip", ""));
    std::string item;
    while (std::getline(list, item, ',')) {
      if (item.size() != 1 || item[0] < '1' || item[0] > '5') {
        std::cerr << "logger_bench: --skip '" << item << "': the parts are 1 to 5\n";
        return 2;
      }
      skip.insert(std::stoi(item));
    }
  }
  try {
    char dir_template[] = "/tmp/sp_logger_bench.XXXXXX";
    const std::string dir = ::mkdtemp(dir_template);
    PrivateServer server(std::string(SP_SOURCE_DIR) + "/scripts/mariadb", dir + "/db", true);
    server.Start();
    std::cout << "private MariaDB server in " << server.dir() << "\n";
    for (const std::string& sql : server_sql) {
      DbConnection::Open(server.AdminTarget(""), false)->Execute(sql, sql);
      std::cout << "  " << sql << "\n";
    }
    if (!skip.count(1)) InsertMethods(server);
    if (!skip.count(2)) WriterThroughput(server);
    if (!skip.count(3)) BesideTheSim(server, seconds, dir);
    if (!skip.count(4)) HighestMultiple(server, seconds, dir);
    if (!skip.count(5)) StoragePerStep(server, seconds);
    server.Stop();
    std::filesystem::remove_all(dir);
  } catch (const std::exception& e) {
    std::cerr << "logger_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
