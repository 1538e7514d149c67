#include "simpartner/sequencer/check.h"

#include <cmath>
#include <filesystem>
#include <system_error>

#include "simpartner/actuator_t.hpp"
#include "simpartner/client/command.h"
#include "simpartner/client/errors.h"
#include "simpartner/data_paths.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/model_message.h"
#include "simpartner/sensor_kinds.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner::sequencer {
namespace {

std::string Qualified(const std::string& robot, const std::string& name) {
  return robot.empty() ? name : robot + "/" + name;
}

}  // namespace

DiagnosticList CheckSequence(const Sequence& sequence, const model_t& model, Plan* plan) {
  DiagnosticList diagnostics;
  client::Catalog catalog;
  try {
    catalog = client::Catalog::FromModel(model);
  } catch (const client::ClientError& e) {
    diagnostics.Add(sequence.file, 0, "", std::string("the model cannot be used: ") + e.what());
    return diagnostics;
  }
  Plan out;
  auto add = [&](int line, const std::string& element, const std::string& message) {
    diagnostics.Add(sequence.file, line, element, message);
  };
  auto robot_of = [&](const std::string& robot) {
    return robot.empty() ? sequence.robot : robot;
  };
  if (!sequence.robot.empty()) {
    bool known = false;
    for (const std::string& r : catalog.robot_names()) known |= r == sequence.robot;
    if (!known) {
      std::string robots;
      for (const std::string& r : catalog.robot_names()) robots += (robots.empty() ? "'" : ", '") + r + "'";
      add(sequence.line, "sequence", "robot '" + sequence.robot + "' is not in the model (it has " +
                                         (robots.empty() ? std::string("none") : robots) + ")");
    }
  }
  for (const Segment& segment : sequence.segments) {
    PlannedSegment planned;
    planned.source = &segment;
    for (const Command& c : segment.commands) {
      PlannedCommand p;
      p.source = &c;
      try {
        p.target = c.target.empty() ? catalog.FindByPort(c.port)
                                    : catalog.Find(Qualified(robot_of(c.robot), c.target));
      } catch (const client::UnknownTarget& e) {
        add(c.line, c.element, e.what());
        continue;
      }
      int8_t action = c.action;
      if (action == kOriginal) {
        // The original's command string to whatever has the port.
        if (p.target.is_actuator() || p.target.lcm_kind == sensor_t::KIND_ECHO)
          action = command_t::ACTION_SET;
        else
          action = c.text.empty() ? command_t::ACTION_READ : command_t::ACTION_SENSOR_PARAMS;
      }
      try {
        p.message = client::BuildCommandFromText(p.target, action, c.text);
      } catch (const client::ClientError& e) {
        add(c.line, c.element, e.what());
        continue;
      }
      planned.commands.push_back(std::move(p));
    }
    if (segment.wait) {
      const Wait& w = *segment.wait;
      planned.wait.source = &w;
      if (w.kind == Wait::Kind::kJoint) {
        const std::string name = Qualified(robot_of(w.robot), w.joint);
        try {
          planned.wait.joint = catalog.JointIndex(name);
          const joint_t& joint = model.joints[static_cast<size_t>(planned.wait.joint)];
          if (w.axis >= std::max<int>(1, joint.num_axes))
            add(w.line, "wait", "joint '" + w.joint + "' has " + std::to_string(joint.num_axes) +
                                    " axes; axis " + std::to_string(w.axis) + " does not exist");
        } catch (const client::ClientError& e) {
          add(w.line, "wait", e.what());
        }
      } else if (w.kind == Wait::Kind::kSensor) {
        try {
          const client::Target& t = catalog.Find(Qualified(robot_of(w.robot), w.sensor));
          if (!t.is_sensor()) {
            add(w.line, "wait", "'" + w.sensor + "' is an actuator (" + t.kind_name() +
                                    "), not a sensor");
          } else {
            const sensor_t& sensor = model.sensors[static_cast<size_t>(t.index)];
            const int size = ReadingSize(sensor);
            if (w.index >= size)
              add(w.line, "wait", "sensor '" + w.sensor + "' (" + t.kind_name() + ") reads " +
                                      std::to_string(size) + " values; index " +
                                      std::to_string(w.index) + " does not exist");
            planned.wait.sensor = t.index;
            planned.wait.sensor_name = t.name;
            planned.wait.read_on_request = !(sensor.rate > 0);
          }
        } catch (const client::ClientError& e) {
          add(w.line, "wait", e.what());
        }
      }
    }
    out.segments.push_back(std::move(planned));
  }
  for (const client::Target& t : catalog.targets())
    if (t.is_actuator() && t.lcm_kind == actuator_t::KIND_JOINT_VELOCITY)
      out.wheel_motors.push_back(t);
  if (diagnostics.empty() && plan != nullptr) *plan = std::move(out);
  return diagnostics;
}

std::string FindSequenceWorld(const Sequence& sequence) {
  if (sequence.world.empty()) return "";
  namespace fs = std::filesystem;
  auto usable = [](const fs::path& p) {  // as FindDataFile: the loader says why a FIFO is not
    std::error_code error;
    return fs::exists(p, error) && !fs::is_directory(p, error);
  };
  std::vector<DataCandidate> tried;
  if (fs::path(sequence.world).is_relative()) {
    const fs::path beside =
        (fs::path(sequence.file).parent_path() / sequence.world).lexically_normal();
    if (usable(beside)) return beside.string();
    tried.push_back({beside.string(), "next to the sequence"});
  }
  try {
    return model::FindWorldFile(sequence.world);
  } catch (const DataFileNotFound& e) {
    tried.insert(tried.end(), e.tried().begin(), e.tried().end());
  }
  DiagnosticList diagnostics;
  diagnostics.Add(sequence.file, sequence.line, "sequence",
                  "world '" + sequence.world + "' is not found; tried:\n" +
                      FormatCandidates(tried) + "(" + DescribeDataLookup() + ")");
  throw ConfigError(diagnostics);
}

std::string WorldForSequence(const Sequence& sequence, const std::string& given) {
  const std::string named = FindSequenceWorld(sequence);
  if (named.empty()) return given;
  if (given.empty()) return named;
  std::error_code error;
  if (std::filesystem::equivalent(given, named, error)) return given;
  DiagnosticList diagnostics;
  diagnostics.Add(sequence.file, sequence.line, "sequence",
                  "the sequence is made for world '" + sequence.world + "' (" + named +
                      "), not for '" + given +
                      "'; leave the world out to use the sequence's, or give that one");
  throw ConfigError(diagnostics);
}

model_t ModelFromWorld(const model::World& world) { return model::ModelMessageFromWorld(world); }

}  // namespace simpartner::sequencer
