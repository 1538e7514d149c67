#include "simpartner/sequencer/player.h"

#include <poll.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <ostream>
#include <thread>

#include "simpartner/client/client.h"
#include "simpartner/command_shape.h"
#include "simpartner/sequencer/check.h"
#include "simpartner/status_t.hpp"

namespace simpartner::sequencer {
namespace {

using Clock = std::chrono::steady_clock;

// Commands sent per pass of the loop (about a millisecond): a burst of
// thousands would overrun the sim's UDP receive buffer.
constexpr size_t kSendPerPass = 50;
// Commands sent and not yet answered; the sim queues at most 10000.
constexpr size_t kMaxInFlight = 2000;
// A command whose step has passed gets its reply within this [s wall].
constexpr double kReplyGrace = 2.0;
// Sensors that publish only when asked are read this often during a wait [s sim].
constexpr double kReadEvery = 0.05;
// Missing replies reported one by one; the rest are counted.
constexpr size_t kReportedUnanswered = 10;
// How far ahead of the sim's newest step a segment's first commands are
// due [s wall]: they must reach the sim before it passes their step. On a
// loaded machine a state reached the sequencer, and its commands the sim,
// 131 ms after the sim was at the state's step (MultiHostTest, both cores
// busy): with a lead of 0.1 s the sim refused them as late.
constexpr double kLeadSeconds = 0.5;

std::string Fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string Short(std::string text) {
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

// Why playing stopped: the file line (0 when none) and the reason.
struct Stop {
  int line = 0;
  std::string reason;
};

class Player {
 public:
  Player(const Sequence& sequence, const PlayOptions& options, std::ostream& out,
         std::ostream& err)
      : sequence_(sequence), options_(options), out_(out), err_(err) {}

  ExitCode Run() {
    client::ClientOptions co;
    co.url = options_.url;  // the client asks for a large socket buffer
    co.program = "sequencer";
    co.model_timeout = options_.model_timeout;
    try {
      client_ = std::make_unique<client::Client>(co);
    } catch (const client::NoSim& e) {
      err_ << sequence_.file << ": not played: " << e.what() << "\n";
      return kNoSim;
    } catch (const client::ClientError& e) {
      err_ << sequence_.file << ": not played: " << e.what() << "\n";
      return kNoSim;
    }
    model_ = client_->model();
    const DiagnosticList problems = CheckSequence(sequence_, *model_, &plan_);
    if (!problems.empty()) {
      err_ << problems.Format() << "\n";
      err_ << sequence_.file << ": not played: " << problems.size()
           << " problem(s) against the model of '" << model_->world_file << "'; nothing was sent\n";
      return kInvalid;
    }
    dt_ = model_->step_size;
    simulation_id_ = model_->simulation_id;
    if (!(dt_ > 0)) {
      err_ << sequence_.file << ": not played: the sim's model has step size " << dt_ << "\n";
      return kNoSim;
    }
    try {
      const std::optional<Stop> stop = Loop();
      if (!stop) return kDone;
      Fail(*stop);
    } catch (const client::ClientError& e) {
      Fail(Stop{0, e.what()});
    }
    return kStopped;
  }

 private:
  struct InFlight {
    const PlannedCommand* command;
    int64_t step;
    std::optional<Clock::time_point> due_seen;  // when the sim first passed its step
  };

  int64_t Steps(double seconds) const { return std::llround(seconds / dt_); }

  // The newest step the sim reported (state or status), and whether it runs.
  int64_t NowStep(bool* paused) {
    int64_t step = -1;
    *paused = false;
    if (const std::optional<state_t> s = client_->LatestState();
        s && s->simulation_id == simulation_id_)
      step = s->step;
    if (const std::optional<status_t> st = client_->LatestStatus();
        st && st->simulation_id == simulation_id_) {
      *paused = st->run_state == status_t::RUN_PAUSED;
      step = std::max(step, st->step);
      if (st->run_state == status_t::RUN_FAULTED) faulted_ = *st;
      if (st->run_state == status_t::RUN_STOPPED) stopped_ = true;
    }
    return step;
  }

  // Steps the commands of a new segment need to reach the sim before the
  // first is due: kLeadSeconds of wall time at the sim's pace.
  int64_t Lead(bool paused) {
    if (paused) return 1;
    double factor = 1.0;
    if (const std::optional<status_t> st = client_->LatestStatus())
      factor = st->target_speed <= 0 ? std::max(1.0, st->real_time_factor)
                                     : std::max({1.0, st->real_time_factor, st->target_speed});
    return std::max<int64_t>(1, Steps(kLeadSeconds * factor));
  }

  std::optional<Stop> Loop() {
    // The sim's step now: a state, or a status (every second, paused too).
    const auto wait_start = Clock::now();
    bool paused = false;
    int64_t now = NowStep(&paused);
    while (now < 0 && Clock::now() - wait_start < std::chrono::duration<double>(options_.silence_timeout)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      now = NowStep(&paused);
    }
    if (now < 0) return Stop{0, "the sim sends neither SIM_STATE nor SIM_STATUS"};
    if (options_.speed) client_->SetSpeed(*options_.speed);
    int64_t anchor = options_.from_zero ? 0 : now + Lead(paused);
    out_ << sequence_.file << ": version " << sequence_.version << ", "
         << sequence_.CommandCount() << " commands, " << sequence_.segments.size()
         << " segment(s); world '" << model_->world_file << "', sim at step " << now
         << (paused ? " (paused)" : "") << "; first step of the sequence " << anchor << std::endl;
    bool resumed = !options_.resume;
    Clock::time_point last_full_scan = Clock::now();
    std::map<int64_t, InFlight> by_request;
    for (size_t s = 0; s < plan_.segments.size(); ++s) {
      const PlannedSegment& segment = plan_.segments[s];
      size_t next = 0, next_note = 0;
      bool waiting = false;
      int64_t wait_from = 0, last_read = -1000000;
      while (true) {
        if (StopRequested())
          return Stop{CurrentLine(segment, next), "interrupted (SIGINT or SIGTERM)"};
        if (std::optional<client::SimRestarted> restart = client_->PendingRestart())
          return Stop{CurrentLine(segment, next), std::string("the sim restarted under the sequence: ") + restart->what()};
        if (client_->SecondsSinceHeard() > options_.silence_timeout)
          return Stop{CurrentLine(segment, next),
                      "the sim went silent: nothing on SIM_STATE or SIM_STATUS for " +
                          Fixed(options_.silence_timeout, 1) + " s"};
        now = NowStep(&paused);
        if (faulted_) {
          std::string why;
          for (const warning_t& w : faulted_->warnings) why += "; " + w.source + ": " + w.message;
          return Stop{CurrentLine(segment, next), "the sim faulted at step " +
                                                      std::to_string(faulted_->step) + why};
        }
        if (stopped_) {
          // A sim that quits after the sequence's end (its duration) leaves
          // nothing undone but the replies still on their way.
          const bool at_end = s + 1 == plan_.segments.size() && next == segment.commands.size() &&
                              now >= anchor + Steps(segment.source->end);
          if (!at_end) return Stop{CurrentLine(segment, next), "the sim stopped (quit)"};
          unanswered_ += by_request.size();
          by_request.clear();
        }
        // Send what is due within the window.
        const int64_t horizon = now + std::max<int64_t>(1, Steps(options_.window));
        size_t sent = 0;
        while (next < segment.commands.size() && sent < kSendPerPass &&
               by_request.size() < kMaxInFlight) {
          const PlannedCommand& c = segment.commands[next];
          const int64_t step = anchor + Steps(c.source->time);
          if (step > horizon) break;
          command_t message = c.message;
          message.apply_at_step = step;
          const int64_t id = client_->Send(message);
          by_request.emplace(id, InFlight{&c, step, std::nullopt});
          ++next;
          ++sent;
        }
        if (!resumed && (next > 0 || segment.commands.empty())) {
          client_->Resume();
          resumed = true;
        }
        // Replies: an accepted one comes when its step is applied, a
        // refusal at once; so commands not yet due are looked at only every
        // 20 ms (request ids, the map's order, follow the steps).
        const bool full_scan = Clock::now() - last_full_scan > std::chrono::milliseconds(20);
        if (full_scan) last_full_scan = Clock::now();
        for (auto it = by_request.begin(); it != by_request.end();) {
          if (!full_scan && it->second.step > now) break;
          if (std::optional<command_reply_t> reply = client_->TakeReply(it->first)) {
            const PlannedCommand& c = *it->second.command;
            if (!reply->accepted)
              return Stop{c.source->line, c.source->element + " " + c.target.name + " '" +
                                              Short(c.source->text) + "' refused by the sim: " +
                                              reply->reason};
            if (!options_.quiet) Progress(c, reply->applied_at_step);
            it = by_request.erase(it);
            continue;
          }
          InFlight& f = it->second;
          if (now > f.step) {
            if (!f.due_seen) f.due_seen = Clock::now();
            // A reply lost in a full socket buffer (the state stream of a
            // sim running as fast as possible is large) is not a refusal:
            // say so and go on.
            if (Clock::now() - *f.due_seen > std::chrono::duration<double>(kReplyGrace)) {
              if (++unanswered_ <= kReportedUnanswered)
                err_ << sequence_.file << ":" << f.command->source->line
                     << ": warning: no reply from the sim for " << f.command->target.name
                     << " (due at step " << f.step << "); lost on the bus? going on"
                     << (unanswered_ == kReportedUnanswered ? " (further ones are only counted)" : "")
                     << std::endl;
              it = by_request.erase(it);
              continue;
            }
          }
          ++it;
        }
        // Comments, when the sim reaches them.
        while (next_note < segment.source->notes.size() &&
               now >= anchor + Steps(segment.source->notes[next_note].time)) {
          const Note& note = segment.source->notes[next_note++];
          if (!options_.quiet)
            out_ << "t=" << Fixed(now * dt_, 3) << " s  line " << note.line << ": # " << note.text
                 << std::endl;
        }
        const bool all_sent = next == segment.commands.size();
        if (segment.source->wait) {
          const PlannedWait& w = segment.wait;
          const Wait& source = *w.source;
          if (all_sent && !waiting && now >= anchor + Steps(source.start)) {
            waiting = true;
            wait_from = anchor + Steps(source.start);
            if (!options_.quiet)
              out_ << "t=" << Fixed(now * dt_, 3) << " s  line " << source.line << ": wait for "
                   << source.Describe() << std::endl;
          }
          if (waiting) {
            std::optional<int64_t> met = Met(w, wait_from, now, &last_read);
            if (met) {
              if (!options_.quiet)
                out_ << "t=" << Fixed(*met * dt_, 3) << " s  line " << source.line << ": "
                     << source.Describe() << ": met at step " << *met << std::endl;
              anchor = std::max(*met, now) + Lead(paused);
              break;  // on to the next segment; replies are still collected there
            }
            if (std::isfinite(source.timeout) && now > wait_from + Steps(source.timeout))
              return Stop{source.line, "wait for " + source.Describe() + ": not met within " +
                                           Fixed(source.timeout, 3) + " s of sim time"};
          }
        } else if (all_sent && by_request.empty() && now >= anchor + Steps(segment.source->end)) {
          if (s + 1 == plan_.segments.size()) {
            out_ << sequence_.file << ": done at t=" << Fixed(now * dt_, 3) << " s (step " << now
                 << ")";
            if (unanswered_ > 0) out_ << "; " << unanswered_ << " command(s) had no reply";
            out_ << std::endl;
            return std::nullopt;
          }
          break;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(500));
      }
    }
    return std::nullopt;
  }

  // The step at which the wait's condition holds, if it does now.
  std::optional<int64_t> Met(const PlannedWait& w, int64_t from, int64_t now, int64_t* last_read) {
    const Wait& source = *w.source;
    switch (source.kind) {
      case Wait::Kind::kTime: {
        const std::optional<state_t> s = client_->LatestState();
        if (s && s->simulation_id == simulation_id_ && s->sim_time >= source.sim_time - 0.5 * dt_)
          return s->step;
        if (now * dt_ >= source.sim_time - 0.5 * dt_) return now;
        return std::nullopt;
      }
      case Wait::Kind::kJoint: {
        const std::optional<state_t> s = client_->LatestState();
        if (!s || s->simulation_id != simulation_id_ || s->step < from) return std::nullopt;
        if (static_cast<size_t>(w.joint) >= s->joints.size()) return std::nullopt;
        const double position = s->joints[static_cast<size_t>(w.joint)].position[source.axis];
        if (std::abs(position - source.angle) <= source.tolerance) return s->step;
        return std::nullopt;
      }
      case Wait::Kind::kSensor: {
        if (w.read_on_request && now - *last_read >= Steps(kReadEvery)) {
          *last_read = now;
          const std::shared_ptr<const client::Catalog> catalog = client_->catalog();
          for (const client::Target& t : catalog->targets()) {
            if (t.is_sensor() && t.index == w.sensor) {
              const int64_t id = client_->Send(client::Read(t));
              reads_.push_back(id);
            }
          }
        }
        while (reads_.size() > 100) {  // replies to our reads are not needed
          client_->TakeReply(reads_.front());
          reads_.pop_front();
        }
        const std::optional<sensor_reading_t> r = client_->LatestReading(w.sensor_name);
        if (!r || r->simulation_id != simulation_id_ || r->step < from) return std::nullopt;
        if (static_cast<size_t>(source.index) >= r->values.size()) return std::nullopt;
        const double v = r->values[static_cast<size_t>(source.index)];
        if (source.above ? v > source.threshold : v < source.threshold) return r->step;
        return std::nullopt;
      }
    }
    return std::nullopt;
  }

  bool StopRequested() const {
    if (options_.stop_fd < 0) return false;
    pollfd fd{options_.stop_fd, POLLIN, 0};
    return ::poll(&fd, 1, 0) > 0 && (fd.revents & POLLIN) != 0;
  }

  static int CurrentLine(const PlannedSegment& segment, size_t next) {
    if (next < segment.commands.size()) return segment.commands[next].source->line;
    if (segment.source->wait) return segment.source->wait->line;
    if (!segment.commands.empty()) return segment.commands.back().source->line;
    return 0;
  }

  void Progress(const PlannedCommand& c, int64_t applied_at_step) {
    out_ << "t=" << Fixed(applied_at_step * dt_, 3) << " s  line " << c.source->line << ": "
         << SpellAction(c.message.action).sequence_element << " " << c.target.name;
    if (!c.source->text.empty()) out_ << " " << Short(c.message.text.empty() ? c.source->text : c.message.text);
    out_ << std::endl;  // a user or a test follows the lines as they come
  }

  void Fail(const Stop& stop) {
    err_ << sequence_.file;
    if (stop.line > 0) err_ << ":" << stop.line;
    err_ << ": stopped: " << stop.reason << "\n";
    StopWheels();
  }

  // Every velocity-controlled actuator to zero velocity, at once: on the
  // sim the sequence ran against, or, after a restart, on the new one.
  void StopWheels() {
    try {
      std::shared_ptr<const client::Catalog> catalog = client_->catalog();
      if (client_->PendingRestart()) catalog = client_->Relearn(1.0);
      const std::vector<command_t> stops = client::StopWheelsCommands(*catalog);
      for (const command_t& c : stops) client_->Send(c);
      err_ << sequence_.file << ": sent zero velocity to " << stops.size() << " wheel motor(s)\n";
    } catch (const client::ClientError& e) {
      err_ << sequence_.file << ": could not stop the wheel motors: " << e.what() << "\n";
    }
  }

  const Sequence& sequence_;
  const PlayOptions& options_;
  std::ostream& out_;
  std::ostream& err_;
  std::unique_ptr<client::Client> client_;
  std::shared_ptr<const model_t> model_;
  Plan plan_;
  double dt_ = 0.0;
  int64_t simulation_id_ = 0;
  std::optional<status_t> faulted_;
  bool stopped_ = false;
  std::deque<int64_t> reads_;
  size_t unanswered_ = 0;
};

}  // namespace

ExitCode Play(const Sequence& sequence, const PlayOptions& options, std::ostream& out,
              std::ostream& err) {
  Player player(sequence, options, out, err);
  return player.Run();
}

}  // namespace simpartner::sequencer
