// simpartner-logger: the receive loop (this thread) hands records to a
// bounded queue that spills to the spool on disk; a writer thread takes
// them in order and writes them into the database in batches, retrying for
// as long as the server is away or refuses writes. Nothing received is
// dropped: at shutdown what could not be written stays in the spool for the
// next run.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/bus_signing.h"
#include "simpartner/bus_url.h"
#include "simpartner/logger/db.h"
#include "simpartner/logger/receiver.h"
#include "simpartner/logger/record_queue.h"
#include "simpartner/logger/reporter.h"
#include "simpartner/logger/spool.h"
#include "simpartner/logger/writer.h"
#include "simpartner/parameters.h"

namespace simpartner::logger {

struct LoggerOptions {
  std::string lcm_url = kDefaultLcmUrl;
  DbTarget db;
  std::string spool_dir = "state/logger-spool";
  int log_interval = 1;  // 1 = every step (logEveryStep=1), else logInterval
  InsertMethod insert_method = InsertMethod::kAuto;
  uint64_t queue_bytes = 64u << 20;       // memory queue; beyond it records spill to disk
  uint64_t spool_segment_bytes = 64u << 20;
  double status_period = 10.0;  // [s] between status lines
  double drain_timeout = 10.0;  // [s] writing on after a stop request
  double retry_period = 1.0;    // [s] between attempts while the server fails
  double sim_silence = 10.0;    // [s] without SIM_STATE/SIM_STATUS: the sim died, close it
  double stall_report = 3.0;    // [s] a database call may take before it is reported
  std::string sender;           // in SIM_MODEL_REQUEST
  std::string tag;              // Simulation.tag of what it logs; "" = NULL
};

// Log-scale histogram of lags (about 2 % resolution) for percentiles.
class LagHistogram {
 public:
  void Add(int64_t micros);
  uint64_t count() const { return count_; }
  // Microseconds below which the fraction p (0..1) of the lags lie.
  double Percentile(double p) const;
  int64_t max() const { return max_; }

 private:
  static constexpr int kBucketsPerDecade = 100;
  std::vector<uint64_t> buckets_ = std::vector<uint64_t>(10 * kBucketsPerDecade + 1, 0);
  uint64_t count_ = 0;
  int64_t max_ = 0;
};

struct LoggerStats {
  ReceiverStats receiver;
  QueueStats queue;
  uint64_t states_written = 0;
  uint64_t states_present = 0;
  uint64_t rows_written = 0;
  uint64_t gaps = 0;
  uint64_t missing_steps = 0;
  uint64_t states_repaired = 0;
  uint64_t unwritable = 0;
  uint64_t transactions = 0;
  uint64_t write_failures = 0;
  LagHistogram lag;        // step published -> its rows committed
  bool db_failing = false;
  std::string db_problem;  // last failure, while failing
  double db_stalled_s = 0; // a database call has waited this long (0: none waiting)
};

class Logger {
 public:
  // Opens the spool and the bus. Throws SpoolError, or Error when the bus
  // cannot be opened.
  Logger(LoggerOptions options, Reporter* reporter);
  ~Logger();

  // Receives until stop_fd is readable, then lets the writer finish (at
  // most drain_timeout) and saves what is left into the spool. Returns the
  // exit status: 0, or 1 if records could be saved neither to the database
  // nor to the spool.
  int Run(int stop_fd);
  LoggerStats Stats() const;
  // One line: what was received, written, waiting, lost.
  std::string StatusLine() const;

 private:
  void WriterLoop();
  // On a stop: handles the messages already waiting on the bus socket.
  void ReadWhatTheBusHolds();
  void ReportFailure(const std::string& problem, const std::string& key);
  // Receive thread: says when a database call has not returned for
  // stall_report seconds (every few seconds while it waits), and when it
  // returns.
  void CheckStall();
  // The writer marks each database call: its start (steady clock, ns; 0 =
  // none under way) and a sequence number.
  void CallStarted();
  void CallEnded();

  LoggerOptions options_;
  Reporter* reporter_;
  std::unique_ptr<Spool> spool_;
  std::unique_ptr<RecordQueue> queue_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::optional<BusSigning> signing_;  // SIMPARTNER_BUS_KEY; before the receiver that uses it
  std::unique_ptr<Receiver> receiver_;
  std::thread writer_;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> save_failed_{false};
  std::chrono::steady_clock::time_point drain_deadline_{};
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  mutable std::mutex stats_mutex_;
  LoggerStats stats_;  // writer's part
  std::string last_failure_key_;
  std::atomic<int64_t> call_started_ns_{0};
  std::atomic<uint64_t> call_seq_{0};
  uint64_t stall_reported_seq_ = 0;  // receive thread: the call reported as stalled
  std::chrono::steady_clock::time_point stall_reported_at_{};
  double stall_reported_s_ = 0;
  std::chrono::steady_clock::time_point last_failure_report_{};
};

}  // namespace simpartner::logger
