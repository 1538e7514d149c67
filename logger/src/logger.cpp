#include "simpartner/logger/logger.h"

#include <poll.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "simpartner/bus_exposure.h"
#include "simpartner/sender.h"
#include "simpartner/socket_backlog.h"

namespace simpartner::logger {
namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kBatchRecords = 1000;
constexpr uint64_t kBatchBytes = 16u << 20;
// At real time a batch collects ~50 steps (a transaction per 50 ms): big
// enough for LOAD DATA, which costs the server a quarter less per row.
constexpr size_t kMinBatchRecords = 50;
constexpr auto kLinger = std::chrono::milliseconds(50);
constexpr auto kFailureReminder = std::chrono::seconds(30);
// On a stop, what was sent before it is read: until the bus is quiet, or
// the followed sim's messages are stamped at or after the stop (a sim
// publishing on), or for at most kStopReadLimit (a sim whose clock is
// behind ours). Quiet is nothing through LCM in kStopQuietPolls polls of
// kQuietPollMs, each returning within twice its time (a logger stopped or
// starved of CPU meanwhile was not listening: wall time alone once ended
// a starved logger's stop with 1,490 states waiting), and no datagram
// waiting in its sockets. A niced logger on a loaded machine can be
// seconds of states behind, the run's end among them; scripts/run gives
// the logger 120 s to stop, drain_timeout's writing included.
constexpr int kQuietPollMs = 10;
constexpr int kStopQuietPolls = 10;
constexpr auto kStopReadLimit = std::chrono::seconds(30);

std::string Megabytes(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
  return text;
}

std::string Ms(double micros) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", micros / 1000.0);
  return text;
}

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

void LagHistogram::Add(int64_t micros) {
  const double value = std::max<double>(1.0, static_cast<double>(micros));
  const int bucket = std::min<int>(static_cast<int>(buckets_.size()) - 1,
                                   static_cast<int>(std::log10(value) * kBucketsPerDecade));
  ++buckets_[static_cast<size_t>(bucket)];
  ++count_;
  max_ = std::max(max_, micros);
}

double LagHistogram::Percentile(double p) const {
  if (count_ == 0) return 0.0;
  const double rank = p * static_cast<double>(count_);
  uint64_t seen = 0;
  for (size_t b = 0; b < buckets_.size(); ++b) {
    seen += buckets_[b];
    if (static_cast<double>(seen) >= rank)
      // The bucket's upper edge, but never above the largest lag seen.
      return std::min(static_cast<double>(max_),
                      std::pow(10.0, static_cast<double>(b + 1) / kBucketsPerDecade));
  }
  return static_cast<double>(max_);
}

Logger::Logger(LoggerOptions options, Reporter* reporter)
    : options_(std::move(options)), reporter_(reporter) {
  options_.lcm_url = WithReceiveBuffer(options_.lcm_url);
  spool_ = std::make_unique<Spool>(options_.spool_dir, options_.spool_segment_bytes,
                                   [this](const std::string& text) { reporter_->Say(text); });
  const uint64_t waiting = spool_->StoredBytes();
  if (waiting > 0)
    reporter_->Say("spool " + options_.spool_dir + " holds " + Megabytes(waiting) +
                   " from an earlier run; writing that first");
  // LOAD DATA scratch files of a logger that was killed while writing.
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(options_.spool_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("loaddata-", 0) == 0 && entry.path().extension() == ".tsv")
      std::filesystem::remove(entry.path(), ec);
  }
  queue_ = std::make_unique<RecordQueue>(options_.queue_bytes, spool_.get());
  lcm_ = std::make_unique<lcm::LCM>(options_.lcm_url);
  if (!lcm_->good()) throw Error("cannot open LCM at '" + options_.lcm_url + "'");
  ReceiverOptions receiver_options;
  receiver_options.log_interval = options_.log_interval;
  receiver_options.sender = options_.sender;
  receiver_options.sim_silence = options_.sim_silence;
  try {
    signing_ = BusSigning::FromEnvironment([this](const std::string& line) { reporter_->Say(line); });
  } catch (const BusKeyError& e) {
    throw Error(e.what());
  }
  receiver_options.signing = signing_ ? &*signing_ : nullptr;
  if (const std::string open = BusExposureWarning(options_.lcm_url, signing_.has_value());
      !open.empty())
    reporter_->Say("warning: " + open);
  receiver_ = std::make_unique<Receiver>(lcm_.get(), queue_.get(), receiver_options, reporter_);
}

Logger::~Logger() {
  if (writer_.joinable()) {
    stopping_ = true;
    queue_->Wake();
    wake_.notify_all();
    writer_.join();
  }
}

void Logger::ReportFailure(const std::string& problem, const std::string& key) {
  const QueueStats q = queue_->Stats();
  const auto now = Clock::now();
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.db_failing = true;
    stats_.db_problem = problem;
    ++stats_.write_failures;
  }
  if (key == last_failure_key_ && now - last_failure_report_ < kFailureReminder) return;
  last_failure_key_ = key;
  last_failure_report_ = now;
  char retry[32];
  std::snprintf(retry, sizeof retry, "%g", options_.retry_period);
  reporter_->Say(problem + "; keeping every record (" + Megabytes(q.memory_bytes) + " in memory, " +
                 Megabytes(q.spool_stored_bytes) + " in the spool " + options_.spool_dir +
                 "), retrying every " + retry + " s");
}

void Logger::CallStarted() {
  call_seq_.fetch_add(1);
  call_started_ns_.store(std::chrono::duration_cast<std::chrono::nanoseconds>(
                             Clock::now().time_since_epoch())
                             .count());
}

void Logger::CallEnded() { call_started_ns_.store(0); }

void Logger::CheckStall() {
  const int64_t started = call_started_ns_.load();
  const uint64_t seq = call_seq_.load();
  const auto now = Clock::now();
  const double waited =
      started == 0 ? 0.0
                   : static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                             now.time_since_epoch())
                                             .count() -
                                         started) /
                         1e9;
  if (stall_reported_seq_ != 0 && (started == 0 || seq != stall_reported_seq_)) {
    char text[64];
    std::snprintf(text, sizeof text, "%.0f s", std::max(waited, stall_reported_s_));
    reporter_->Say("database server " + options_.db.Server() + " answers again (it had not answered for " +
                   text + " or more)");
    stall_reported_seq_ = 0;
  }
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.db_stalled_s = waited >= options_.stall_report ? waited : 0.0;
  }
  if (waited < options_.stall_report) return;
  if (stall_reported_seq_ == seq && now - stall_reported_at_ < Seconds(5)) return;
  stall_reported_seq_ = seq;
  stall_reported_at_ = now;
  stall_reported_s_ = waited;
  const QueueStats q = queue_->Stats();
  char text[64];
  std::snprintf(text, sizeof text, "%.0f s", waited);
  reporter_->Say("database server " + options_.db.Server() + " has not answered for " + text +
                 " (stopped or overloaded?); keeping every record (" + Megabytes(q.memory_bytes) +
                 " in memory, " + Megabytes(q.spool_stored_bytes) + " in the spool " +
                 options_.spool_dir + ")");
}

void Logger::WriterLoop() {
  WriterOptions writer_options;
  writer_options.method = options_.insert_method;
  writer_options.lcm_url = options_.lcm_url;
  writer_options.log_interval = options_.log_interval;
  writer_options.scratch_dir = options_.spool_dir;
  writer_options.tag = options_.tag;
  DbWriter writer(options_.db, writer_options,
                  [this](const std::string& text) { reporter_->Say(text); });
  Batch batch;
  bool failing = false;
  auto wait_retry = [this] {
    std::unique_lock<std::mutex> lock(wake_mutex_);
    wake_.wait_for(lock, Seconds(options_.retry_period), [this] {
      return stopping_.load() && Clock::now() >= drain_deadline_;
    });
  };
  while (true) {
    if (stopping_ && Clock::now() >= drain_deadline_) break;
    if (batch.empty()) {
      if (stopping_ && queue_->Drained()) break;
      batch = queue_->Take(kBatchRecords, kBatchBytes, std::chrono::milliseconds(50),
                           stopping_ ? 1 : kMinBatchRecords, kLinger);
      if (batch.empty() && writer.connected()) continue;
    }
    try {
      struct CallMark {
        Logger* logger;
        explicit CallMark(Logger* l) : logger(l) { logger->CallStarted(); }
        ~CallMark() { logger->CallEnded(); }
      };
      if (batch.empty()) {
        // Nothing to write yet: connect early so a bad server shows at once.
        CallMark mark(this);
        writer.Connect();
      } else {
        WriteResult result;
        {
          CallMark mark(this);
          result = writer.Write(batch.records);
        }
        queue_->Commit(batch);
        batch = Batch();
        std::lock_guard<std::mutex> lock(stats_mutex_);
        stats_.states_written += result.states_written;
        stats_.states_present += result.states_present;
        stats_.rows_written += result.rows_written;
        stats_.gaps += result.gaps;
        stats_.missing_steps += result.missing_steps;
        stats_.states_repaired += result.states_repaired;
        stats_.unwritable += result.unwritable;
        ++stats_.transactions;
        for (int64_t lag : result.lags_us) stats_.lag.Add(lag);
      }
      if (failing) {
        failing = false;
        last_failure_key_.clear();
        const QueueStats q = queue_->Stats();
        reporter_->Say("database server " + writer.target().Server() + " takes writes again; " +
                       "catching up (" + Megabytes(q.spool_stored_bytes) + " in the spool)");
        std::lock_guard<std::mutex> lock(stats_mutex_);
        stats_.db_failing = false;
        stats_.db_problem.clear();
      }
    } catch (const DbError& e) {
      failing = true;
      std::string what;
      switch (e.kind()) {
        case DbErrorKind::kUnreachable:
          what = "database server " + e.server() + " is unreachable: " + e.detail();
          break;
        case DbErrorKind::kRefused:
          what = "database server " + e.server() + " refuses writes: " + e.detail();
          break;
        case DbErrorKind::kRetry:
          continue;  // deadlock or lock wait: at once
        case DbErrorKind::kOther:
          what = "database server " + e.server() + " failed: " + e.detail();
          break;
      }
      ReportFailure(what, std::to_string(static_cast<int>(e.kind())) + "/" + std::to_string(e.code()));
      wait_retry();
    } catch (const std::exception& e) {
      failing = true;
      ReportFailure(std::string("writing to ") + writer.target().Server() + " failed: " + e.what(),
                    "other");
      wait_retry();
    }
  }
  try {
    if (!batch.empty() || !queue_->Drained()) {
      const size_t saved = queue_->SaveUnwritten(batch);
      const QueueStats q = queue_->Stats();
      reporter_->Say("stopping with " + std::to_string(saved) + " records from memory saved to the spool " +
                     options_.spool_dir + " (" + Megabytes(q.spool_stored_bytes) +
                     " there in all); the next run writes them first");
    }
  } catch (const SpoolError& e) {
    save_failed_ = true;
    reporter_->Say(std::string("could not save the records left in memory: ") + e.what());
  }
  writer.Disconnect();
  DbThreadEnd();
}

int Logger::Run(int stop_fd) {
  writer_ = std::thread([this] { WriterLoop(); });
  receiver_->RequestModel();
  auto next_status = Clock::now() + Seconds(options_.status_period);
  std::string last_status_line;
  while (true) {
    pollfd fds[2] = {{lcm_->getFileno(), POLLIN, 0}, {stop_fd, POLLIN, 0}};
    const int ready = ::poll(fds, 2, 100);
    if (ready > 0 && (fds[1].revents & (POLLIN | POLLHUP))) break;
    if (ready > 0 && (fds[0].revents & POLLIN)) lcm_->handle();
    receiver_->Tick();
    CheckStall();
    if (Clock::now() >= next_status) {
      // Only when something changed: an idle logger does not repeat itself
      // every period.
      std::string line = StatusLine();
      if (line != last_status_line) {
        reporter_->Say(line);
        last_status_line = std::move(line);
      }
      next_status = Clock::now() + Seconds(options_.status_period);
    }
  }
  ReadWhatTheBusHolds();
  drain_deadline_ = Clock::now() + Seconds(options_.drain_timeout);
  stopping_ = true;
  queue_->Wake();
  wake_.notify_all();
  writer_.join();
  reporter_->Say("stopped: " + StatusLine());
  return save_failed_ ? 1 : 0;
}

void Logger::ReadWhatTheBusHolds() {
  const int64_t stop_us = WallMicros();
  const auto start = Clock::now();
  pollfd fd{lcm_->getFileno(), POLLIN, 0};
  bool caught_up = false;  // the bus went quiet, or the sim's stamps passed the stop
  int quiet_polls = 0;
  while (!caught_up && Clock::now() - start < kStopReadLimit) {
    const auto before = Clock::now();
    const int ready = ::poll(&fd, 1, kQuietPollMs);
    if (ready > 0 && (fd.revents & POLLIN)) {
      quiet_polls = 0;
      lcm_->handle();
      receiver_->Tick();
      caught_up = receiver_->Stats().newest_stamp_us >= stop_us;
      continue;
    }
    const bool listened =
        ready == 0 && Clock::now() - before <= std::chrono::milliseconds(2 * kQuietPollMs);
    quiet_polls = listened ? quiet_polls + 1 : 0;
    caught_up = quiet_polls >= kStopQuietPolls && UnreadUdpBytes().value_or(0) == 0;
  }
  const ReceiverStats s = receiver_->Stats();
  if (!caught_up)
    reporter_->Say("stop: still receiving after " +
                   std::to_string(std::chrono::duration_cast<std::chrono::seconds>(kStopReadLimit).count()) +
                   " s of reading what was sent before the stop; the rest is not logged");
  if (s.simulation_id != 0 && !s.followed_ended)
    reporter_->Say("stop: bus simulation " + std::to_string(s.simulation_id) +
                   " had not ended (no RUN_STOPPED heard; last step " + std::to_string(s.last_step) +
                   "): it stays open in the database until a logger hears it stop or go silent");
}

LoggerStats Logger::Stats() const {
  LoggerStats s;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    s = stats_;
  }
  s.receiver = receiver_->Stats();
  s.queue = queue_->Stats();
  return s;
}

std::string Logger::StatusLine() const {
  const LoggerStats s = Stats();
  std::string line;
  if (s.receiver.simulation_id != 0)
    line += "bus simulation " + std::to_string(s.receiver.simulation_id) + " at step " +
            std::to_string(s.receiver.last_step) + "; ";
  else
    line += "no SIM_MODEL seen yet; ";
  line += "written " + std::to_string(s.states_written) + " steps (" + std::to_string(s.rows_written) +
          " rows";
  if (s.states_present > 0) line += ", " + std::to_string(s.states_present) + " already there";
  line += ")";
  if (s.lag.count() > 0)
    line += ", lag p50 " + Ms(s.lag.Percentile(0.5)) + " p99 " + Ms(s.lag.Percentile(0.99));
  line += "; queue " + Megabytes(s.queue.memory_bytes) + ", spool " +
          Megabytes(s.queue.spool_stored_bytes);
  line += "; gaps " + std::to_string(s.gaps) + " (" + std::to_string(s.missing_steps) +
          " steps missing)";
  line += "; bad messages " + std::to_string(s.receiver.BadMessages());
  for (const auto& [channel, c] : s.receiver.channels)
    if (c.malformed + c.invalid + c.unsigned_or_forged > 0)
      line += " [" + channel + ": " + std::to_string(c.malformed) + " malformed, " +
              std::to_string(c.invalid) + " invalid" +
              (c.unsigned_or_forged > 0
                   ? ", " + std::to_string(c.unsigned_or_forged) + " unsigned or forged"
                   : std::string()) +
              "]";
  if (s.receiver.state_conflicts > 0)
    line += "; " + std::to_string(s.receiver.state_conflicts) +
            " conflicting SIM_STATEs (another sender forges states; the first of each step kept)";
  if (s.receiver.dropped_no_model > 0)
    line += "; dropped " + std::to_string(s.receiver.dropped_no_model) + " without a model";
  if (s.receiver.lost_spool_failed > 0)
    line += "; REFUSED " + std::to_string(s.receiver.lost_spool_failed) + " records (" +
            Megabytes(s.receiver.lost_spool_bytes) + ", " + std::to_string(s.receiver.lost_states) +
            " steps, in LogGap): memory queue and spool disk full";
  if (s.receiver.simulations_silent > 0)
    line += "; " + std::to_string(s.receiver.simulations_silent) + " simulations closed (sim silent)";
  if (s.states_repaired > 0)
    line += "; " + std::to_string(s.states_repaired) + " incomplete steps completed";
  if (s.db_stalled_s > 0) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f s", s.db_stalled_s);
    line += std::string("; DATABASE NOT ANSWERING for ") + text;
  }
  if (s.db_failing) line += "; DATABASE FAILING: " + s.db_problem;
  return line;
}

}  // namespace simpartner::logger
