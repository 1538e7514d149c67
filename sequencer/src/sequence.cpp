#include "simpartner/sequencer/sequence.h"

#include <algorithm>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "sequence_dtds.h"
#include "simpartner/bounded_file.h"
#include "simpartner/command_shape.h"
#include "simpartner/command_t.hpp"
#include "simpartner/text.h"
#include "simpartner/xml_document.h"

namespace simpartner::sequencer {
namespace {

using xml::Attribute;
using xml::Child;
using xml::Line;
using xml::Name;

// Where the first element starts, skipping the XML declaration, comments,
// processing instructions and white space; npos if there is none.
size_t FirstElement(const std::string& xml) {
  size_t at = 0;
  while (at < xml.size()) {
    at = xml.find_first_not_of(" \t\r\n", at);
    if (at == std::string::npos) return at;
    if (xml.compare(at, 4, "<!--") == 0) {
      at = xml.find("-->", at + 4);
      if (at == std::string::npos) return at;
      at += 3;
    } else if (xml.compare(at, 2, "<?") == 0) {
      at = xml.find("?>", at + 2);
      if (at == std::string::npos) return at;
      at += 2;
    } else if (xml.compare(at, 3, "\xEF\xBB\xBF") == 0) {
      at += 3;  // UTF-8 byte order mark
    } else {
      return xml[at] == '<' ? at : std::string::npos;
    }
  }
  return std::string::npos;
}

// The original's sequences may be a bare list of <command> elements: they
// are read as version 1 inside the root they lack, inserted on the first
// command's line so that line numbers stay those of the file. Returns the
// text to parse (xml itself when it has a root).
std::string WithRoot(const std::string& xml, const std::string& file_name,
                     std::vector<std::string>* notes) {
  const size_t first = FirstElement(xml);
  if (first == std::string::npos || xml.compare(first, 8, "<command") != 0) return xml;
  if (first + 8 < xml.size() && xml[first + 8] != '>' &&
      !std::isspace(static_cast<unsigned char>(xml[first + 8])))
    return xml;
  notes->push_back(file_name +
                   ": no <sequence> root element: read as the original's version 1 list of "
                   "commands (add <sequence version=\"1\"> ... </sequence> around them to say so)");
  return xml.substr(0, first) + "<sequence version=\"1\">" + xml.substr(first) + "\n</sequence>\n";
}

// The version the root says, 1 or 2; 0 after a diagnostic.
int RootVersion(const xmlNode* root, const std::string& file_name, DiagnosticList* diagnostics) {
  if (Name(root) != "sequence") {
    diagnostics->Add(file_name, Line(root), Name(root),
                     "the root element must be <sequence version=\"1\"> (the original's "
                     "<command> list) or <sequence version=\"2\">");
    return 0;
  }
  const std::optional<std::string> version_text = Attribute(root, "version");
  if (!version_text) {
    diagnostics->Add(file_name, Line(root), "sequence",
                     "no version attribute: add version=\"1\" (the original's <command>/<port> "
                     "format) or version=\"2\"");
    return 0;
  }
  const std::string v = Trim(*version_text);
  if (v != "1" && v != "2") {
    diagnostics->Add(file_name, Line(root), "sequence",
                     "version '" + *version_text + "' is not known (1 or 2)");
    return 0;
  }
  return v == "1" ? 1 : 2;
}

// Parses the file's text and validates it against the DTD of the version
// its root names; nothing, with diagnostics, when either fails.
std::optional<xml::Document> ParseAndValidate(const std::string& xml, const std::string& file_name,
                                              SequenceParseResult* result, int* version) {
  DiagnosticList& diagnostics = result->diagnostics;
  std::optional<xml::Document> doc =
      xml::Document::Parse(WithRoot(xml, file_name, &result->notes), file_name, &diagnostics);
  if (!doc) return std::nullopt;
  *version = RootVersion(doc->root(), file_name, &diagnostics);
  if (*version == 0) return std::nullopt;
  const std::string dtd_name = "sequence_v" + std::to_string(*version) + ".dtd";
  if (!doc->Validate(xml::Dtd{dtd_name, SequenceDtd(*version)}, &diagnostics)) return std::nullopt;
  return doc;
}

// The root's world attribute: a world file's name (a path may lead to it).
void ReadWorldName(const xmlNode* root, Sequence* sequence, DiagnosticList* diagnostics) {
  const std::optional<std::string> world = Attribute(root, "world");
  if (!world) return;
  sequence->world = Trim(*world);
  const std::string& name = sequence->world;
  const std::string extension = ".xml";
  if (name.empty()) {
    xml::AddAt(diagnostics, sequence->file, root,
               "world is empty: give the world file the sequence is made for, e.g. "
               "world=\"pole_task.xml\", or leave the attribute out");
  } else if (name.size() <= extension.size() ||
             name.compare(name.size() - extension.size(), extension.size(), extension) != 0 ||
             name.back() == '/' || name[name.size() - extension.size() - 1] == '/') {
    xml::AddAt(diagnostics, sequence->file, root,
               "world '" + *world + "' is not a world file name (NAME.xml, e.g. pole_task.xml)");
  }
}

// Walks a valid document into segments, keeping every problem it finds.
class Builder {
 public:
  Builder(Sequence* sequence, DiagnosticList* diagnostics, size_t max_commands)
      : sequence_(sequence), diagnostics_(diagnostics), max_commands_(max_commands) {
    sequence_->segments.emplace_back();
  }

  void Block(const xmlNode* parent, double block_start) {
    block_start_ = block_start;
    for (const xmlNode* node : xml::Children(parent)) {
      if (stopped_) break;
      Item(node);
    }
  }

  void Finish() {
    Segment& s = sequence_->segments.back();
    s.end = std::max(s.end, cursor_);
    for (Segment& segment : sequence_->segments) {
      std::stable_sort(segment.commands.begin(), segment.commands.end(),
                       [](const Command& a, const Command& b) { return a.time < b.time; });
      for (const Command& c : segment.commands) segment.end = std::max(segment.end, c.time);
    }
  }

 private:
  void Error(const xmlNode* node, const std::string& message) {
    xml::AddAt(diagnostics_, sequence_->file, node, message);
  }

  // A number attribute; nullopt (with a diagnostic) when absent but
  // required, or not a finite number.
  std::optional<double> Number(const xmlNode* node, const char* attribute, bool required,
                               bool non_negative) {
    const std::optional<std::string> text = Attribute(node, attribute);
    if (!text) {
      if (required) Error(node, std::string(attribute) + " is missing");
      return std::nullopt;
    }
    return NumberText(node, attribute, *text, non_negative);
  }

  std::optional<double> NumberText(const xmlNode* node, const std::string& what,
                                   const std::string& raw, bool non_negative) {
    const std::string text = Trim(raw);
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value)) {
      Error(node, what + " '" + raw + "' is not a number");
      return std::nullopt;
    }
    if (non_negative && value < 0) {
      Error(node, what + " " + FormatNumber(value, 10) + " is negative");
      return std::nullopt;
    }
    return value;
  }

  Segment& Current() { return sequence_->segments.back(); }

  bool Room(const xmlNode* node, size_t more) {
    if (commands_ + more > max_commands_) {
      Error(node, "the sequence unrolls to more than " + std::to_string(max_commands_) +
                      " commands (repeats and ramps included)");
      stopped_ = true;
      return false;
    }
    commands_ += more;
    return true;
  }

  // Target attributes of a version-2 command element.
  bool Target(const xmlNode* node, Command* c) {
    const std::optional<std::string> target = Attribute(node, "target");
    const std::optional<std::string> port = Attribute(node, "port");
    c->robot = Trim(Attribute(node, "robot").value_or(""));
    if (target && port) {
      Error(node, "both target '" + *target + "' and port " + *port + " are given; use one");
      return false;
    }
    if (!target && !port) {
      Error(node, "no target: give target=\"NAME\" or port=\"PORT\"");
      return false;
    }
    if (target) {
      c->target = Trim(*target);
      if (c->target.empty()) {
        Error(node, "target is empty");
        return false;
      }
      return true;
    }
    return Port(node, *port, c);
  }

  bool Port(const xmlNode* node, const std::string& raw, Command* c) {
    const std::string text = Trim(raw);
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || value < 0 || value > 65535) {
      Error(node, "port '" + raw + "' is not a port number (0 for the sequencer, 1025 to 65535)");
      return false;
    }
    if (value != 0 && value <= 1024) {
      Error(node, "port " + text + " is not a legacy port (they are 1025 to 65535; 0 is the sequencer)");
      return false;
    }
    c->port = static_cast<int>(value);
    return true;
  }

  // at="T": the command's time from the block's start; else the cursor.
  bool Time(const xmlNode* node, Command* c) {
    if (const std::optional<std::string> at = Attribute(node, "at")) {
      const std::optional<double> t = NumberText(node, "at", *at, true);
      if (!t) return false;
      c->time = block_start_ + *t;
    } else {
      c->time = cursor_;
    }
    cursor_ = c->time;
    return true;
  }

  void Add(Command c) {
    Current().commands.push_back(std::move(c));
  }

  void Pause(double seconds) { cursor_ += seconds; }

  void Item(const xmlNode* node) {
    const std::string name = Name(node);
    if (name == "command") {
      OriginalCommand(node);
    } else if (ActionOfSequenceElement(name) >= 0) {
      Command c;
      c.line = Line(node);
      c.element = name;
      c.action = static_cast<int8_t>(ActionOfSequenceElement(name));
      if (!Target(node, &c)) return;
      if (c.port == 0 && c.target.empty()) {
        Error(node, "port 0 is the sequencer itself; use <pause seconds=\"...\"/>");
        return;
      }
      if (!Time(node, &c)) return;
      // Numbers or an Echo's text: decided against the model.
      c.text = xml::Text(node);
      if (!Room(node, 1)) return;
      Add(std::move(c));
    } else if (name == "ramp") {
      Ramp(node);
    } else if (name == "pause") {
      const std::optional<double> seconds = Number(node, "seconds", true, true);
      if (seconds) Pause(*seconds);
    } else if (name == "wait") {
      WaitElement(node);
    } else if (name == "repeat") {
      Repeat(node);
    } else if (name == "comment") {
      Current().notes.push_back(Note{Line(node), cursor_, xml::Text(node)});
    } else {
      Error(node, "unknown element");  // the DTD stops this; kept for safety
    }
  }

  void OriginalCommand(const xmlNode* node) {
    Command c;
    c.line = Line(node);
    c.element = "command";
    c.action = kOriginal;
    const xmlNode* port = Child(node, "port");
    const xmlNode* text = Child(node, "commandString");
    if (port == nullptr || text == nullptr) return;  // the DTD requires both
    if (!Port(port, xml::Text(port), &c)) return;
    c.text = xml::Text(text);
    if (c.port == 0) {
      // The sequencer's own port: the command string is a pause [s].
      const std::optional<double> seconds = NumberText(text, "pause", c.text, false);
      if (!seconds) return;
      if (*seconds < 0) {
        Error(text, "negative pause " + FormatNumber(*seconds, 10) + " s on port 0 (the sequencer)");
        return;
      }
      Pause(*seconds);
      return;
    }
    c.time = cursor_;
    if (!Room(node, 1)) return;
    Add(std::move(c));
  }

  void Ramp(const xmlNode* node) {
    Command c;
    c.line = Line(node);
    c.element = "ramp";
    c.action = command_t::ACTION_SET;
    if (!Target(node, &c)) return;
    if (c.port == 0 && c.target.empty()) {
      Error(node, "port 0 is the sequencer itself; a ramp needs an actuator");
      return;
    }
    if (!Time(node, &c)) return;
    const std::optional<double> duration = Number(node, "duration", true, true);
    const std::optional<double> every = Number(node, "every", true, true);
    std::vector<double> from, to;
    std::string error;
    bool ok = duration && every;
    if (!ParseValues(Attribute(node, "from").value_or(""), &from, &error)) {
      Error(node, "from: " + error);
      ok = false;
    }
    if (!ParseValues(Attribute(node, "to").value_or(""), &to, &error)) {
      Error(node, "to: " + error);
      ok = false;
    }
    if (!ok) return;
    if (from.size() != to.size()) {
      Error(node, "from has " + std::to_string(from.size()) + " values and to has " +
                      std::to_string(to.size()) + "; they must match");
      return;
    }
    if (*every <= 0) {
      Error(node, "every must be above 0 s");
      return;
    }
    const double passes = std::floor(*duration / *every + 1e-9);
    if (passes + 1 > static_cast<double>(max_commands_)) {
      Room(node, max_commands_ + 1);
      return;
    }
    const size_t n = static_cast<size_t>(passes);
    if (!Room(node, n + 1)) return;
    const double start = c.time;
    for (size_t k = 0; k <= n; ++k) {
      Command step = c;
      step.time = start + static_cast<double>(k) * *every;
      const double u = n == 0 ? 1.0 : static_cast<double>(k) / static_cast<double>(n);
      std::string text;
      for (size_t i = 0; i < from.size(); ++i) {
        char item[40];
        std::snprintf(item, sizeof item, "%.17g", from[i] + (to[i] - from[i]) * u);
        text += (i ? "," : "") + std::string(item);
      }
      step.text = text;
      Add(std::move(step));
    }
    cursor_ = start + *duration;
  }

  void WaitElement(const xmlNode* node) {
    Wait w;
    w.line = Line(node);
    w.robot = Trim(Attribute(node, "robot").value_or(""));
    const bool has_time = Attribute(node, "time").has_value();
    const bool has_joint = Attribute(node, "joint").has_value();
    const bool has_sensor = Attribute(node, "sensor").has_value();
    if (has_time + has_joint + has_sensor != 1) {
      Error(node, "give exactly one condition: time=\"T\", joint=\"J\" angle=\"A\" "
                  "tolerance=\"E\", or sensor=\"S\" above=\"X\" / below=\"X\"");
      return;
    }
    bool ok = true;
    if (const std::optional<std::string> timeout = Attribute(node, "timeout")) {
      const std::optional<double> t = NumberText(node, "timeout", *timeout, true);
      ok = ok && t.has_value();
      if (t) w.timeout = *t;
    } else if (!has_time) {
      Error(node, "timeout is missing: a wait on a joint or a sensor needs one (seconds of sim time)");
      ok = false;
    }
    if (has_time) {
      w.kind = Wait::Kind::kTime;
      const std::optional<double> t = Number(node, "time", true, true);
      ok = ok && t.has_value();
      if (t) w.sim_time = *t;
    } else if (has_joint) {
      w.kind = Wait::Kind::kJoint;
      w.joint = Trim(*Attribute(node, "joint"));
      const std::optional<double> angle = Number(node, "angle", true, false);
      const std::optional<double> tolerance = Number(node, "tolerance", true, true);
      ok = ok && angle && tolerance;
      if (angle) w.angle = *angle;
      if (tolerance) w.tolerance = *tolerance;
      if (const std::optional<double> axis = Number(node, "axis", false, true)) {
        if (*axis != std::floor(*axis) || *axis > 2) {
          Error(node, "axis " + FormatNumber(*axis, 10) + " must be 0, 1 or 2");
          ok = false;
        }
        w.axis = static_cast<int>(*axis);
      }
    } else {
      w.kind = Wait::Kind::kSensor;
      w.sensor = Trim(*Attribute(node, "sensor"));
      const bool above = Attribute(node, "above").has_value();
      const bool below = Attribute(node, "below").has_value();
      if (above == below) {
        Error(node, "a sensor wait needs one of above=\"X\" or below=\"X\"");
        ok = false;
      } else {
        w.above = above;
        const std::optional<double> x = Number(node, above ? "above" : "below", true, false);
        ok = ok && x.has_value();
        if (x) w.threshold = *x;
      }
      if (const std::optional<double> index = Number(node, "index", false, true)) {
        // Checked before the cast: 1e11 does not fit an int (a fuzzer's find).
        if (*index != std::floor(*index) || *index > 100000) {
          Error(node, "index " + FormatNumber(*index, 10) +
                          " must be a whole number from 0 to 100000");
          ok = false;
        } else {
          w.index = static_cast<int>(*index);
        }
      }
    }
    if (!ok) return;
    if (in_period_repeat_ > 0) {
      Error(node, "a wait cannot be inside a repeat with a period (the period would be "
                  "counted from before the wait)");
      return;
    }
    Segment& s = Current();
    w.start = cursor_;
    s.end = std::max(s.end, cursor_);
    s.wait = w;
    sequence_->segments.emplace_back();
    cursor_ = 0.0;
    block_start_ = 0.0;
  }

  void Repeat(const xmlNode* node) {
    const std::optional<double> count = Number(node, "count", true, true);
    if (!count) return;
    if (*count != std::floor(*count) || *count > 1e6) {
      Error(node, "count " + FormatNumber(*count, 10) + " must be a whole number from 0 to 1000000");
      return;
    }
    std::optional<double> period;
    if (Attribute(node, "period")) {
      period = Number(node, "period", true, true);
      if (!period) return;
    }
    const double outer_start = block_start_;
    const size_t segments_before = sequence_->segments.size();
    const double first = cursor_;
    if (period) ++in_period_repeat_;
    for (int pass = 0; pass < static_cast<int>(*count) && !stopped_; ++pass) {
      if (++passes_ > max_commands_ * 4) {
        Error(node, "the repeats nest to more than " + std::to_string(max_commands_ * 4) +
                        " passes");
        stopped_ = true;
        break;
      }
      if (period) cursor_ = first + pass * *period;
      const double start = cursor_;
      Block(node, start);
      if (!diagnostics_->empty() && pass == 0) break;  // one report per problem, not per pass
    }
    if (period) {
      --in_period_repeat_;
      cursor_ = std::max(cursor_, first + *count * *period);
    }
    // After a wait inside, the enclosing block goes on in the new segment.
    block_start_ = sequence_->segments.size() == segments_before ? outer_start : 0.0;
  }

  Sequence* sequence_;
  DiagnosticList* diagnostics_;
  size_t max_commands_;
  double block_start_ = 0.0;
  double cursor_ = 0.0;
  size_t commands_ = 0;
  size_t passes_ = 0;
  int in_period_repeat_ = 0;
  bool stopped_ = false;
};

}  // namespace

size_t Sequence::CommandCount() const {
  size_t n = 0;
  for (const Segment& s : segments) n += s.commands.size();
  return n;
}

std::string Wait::Describe() const {
  switch (kind) {
    case Kind::kTime: return "sim time " + FormatNumber(sim_time, 10) + " s";
    case Kind::kJoint:
      return "joint " + joint + (axis ? " axis " + std::to_string(axis) : "") + " within " +
             FormatNumber(tolerance, 10) + " of " + FormatNumber(angle, 10);
    case Kind::kSensor:
      return "sensor " + sensor + " value " + std::to_string(index) + (above ? " above " : " below ") +
             FormatNumber(threshold, 10);
  }
  return "";
}

bool ParseValues(const std::string& text, std::vector<double>* values, std::string* error) {
  values->clear();
  if (Trim(text).empty()) return true;
  std::string item;
  std::istringstream in(text);
  int index = 0;
  while (std::getline(in, item, ',')) {
    const std::string trimmed = Trim(item);
    char* end = nullptr;
    const double v = std::strtod(trimmed.c_str(), &end);
    if (trimmed.empty() || *end != '\0' || !std::isfinite(v)) {
      *error = "value " + std::to_string(index + 1) + " '" + trimmed + "' is not a number";
      return false;
    }
    values->push_back(v);
    ++index;
  }
  if (!text.empty() && text.back() == ',') {
    *error = "value " + std::to_string(index + 1) + " '' is not a number";
    return false;
  }
  return true;
}

const std::string& SequenceDtd(int version) {
  static const std::string v1 = kSequenceV1DtdText;
  static const std::string v2 = kSequenceV2DtdText;
  return version == 1 ? v1 : v2;
}

SequenceParseResult ParseSequence(const std::string& xml, const std::string& file_name,
                                  size_t max_commands) {
  SequenceParseResult result;
  int version = 0;
  const std::optional<xml::Document> doc = ParseAndValidate(xml, file_name, &result, &version);
  if (!doc) return result;
  Sequence sequence;
  sequence.file = file_name;
  sequence.version = version;
  sequence.rootless = !result.notes.empty();
  const xmlNode* root = doc->root();
  sequence.line = Line(root);
  sequence.name = Attribute(root, "name").value_or("");
  sequence.robot = Trim(Attribute(root, "robot").value_or(""));
  sequence.description = Attribute(root, "description").value_or("");
  ReadWorldName(root, &sequence, &result.diagnostics);
  Builder builder(&sequence, &result.diagnostics, std::min(max_commands, kMaxCommands));
  builder.Block(root, 0.0);
  builder.Finish();
  if (result.diagnostics.empty()) result.sequence = std::move(sequence);
  return result;
}

SequenceParseResult LoadSequenceFile(const std::string& path) {
  std::string text;
  try {
    text = ReadBoundedFile(path, xml::kMaxDocumentBytes, "sequence files");
  } catch (const FileReadError& e) {
    SequenceParseResult result;
    result.diagnostics.Add(path, 0, "",
                           e.cannot_open() ? std::string("cannot be read: ") + e.what() : e.what());
    return result;
  }
  return ParseSequence(text, path);
}

}  // namespace simpartner::sequencer
