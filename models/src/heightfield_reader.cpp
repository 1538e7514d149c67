// <heightfield>: its grid, extent, scale and position, and the samples,
// each bad one reported at its own line.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "parts.h"
#include "simpartner/text.h"

namespace simpartner::model::detail {
namespace {

class HeightfieldReading {
 public:
  HeightfieldReading(Reader& reader, const xmlNode* node, Heightfield* field)
      : reader_(reader), node_(node), field_(*field) {}

  void ReadGrid() {
    field_.rows = Count("rows");
    field_.columns = Count("columns");
    field_.width = Positive("width");
    field_.depth = Positive("depth");
    for (const char* tag : {"width", "depth"}) {
      const double extent = std::string(tag) == "width" ? field_.width : field_.depth;
      if (extent > limits::kMaxCoordinate)
        reader_.Error(xml::Child(node_, tag), std::string("heightfield ") + tag + " " +
                                                  FormatNumber(extent, 10) + " m is out of range (0, " +
                                                  FormatNumber(limits::kMaxCoordinate, 10) + "] m");
    }
  }

  void ReadPlacement() {
    bool ok = true;
    field_.scale = reader_.NumberOr(node_, "scale", 1.0, "heightfield", &ok);
    field_.offset = reader_.NumberOr(node_, "offset", 0.0, "heightfield", &ok);
    field_.thickness = reader_.NumberOr(node_, "thickness", 1.0, "heightfield", &ok);
    const xmlNode* thickness = xml::Child(node_, "thickness");
    if (field_.thickness <= 0.0)
      reader_.Error(thickness, "heightfield thickness must be positive, got " +
                                   FormatNumber(field_.thickness, 10));
    else if (field_.thickness > limits::kMaxCoordinate)
      reader_.Error(thickness, "heightfield thickness " + FormatNumber(field_.thickness, 10) +
                                   " m is out of range (0, " +
                                   FormatNumber(limits::kMaxCoordinate, 10) + "] m");
    const xmlNode* p = xml::Child(node_, "position");
    if (p == nullptr) return;
    if (const auto position = reader_.Vector(p, "heightfield position")) {
      field_.position = *position;
      if (!CoordinatesInRange(*position))
        reader_.Error(p, "heightfield position " + VectorText(*position) +
                             " m is out of range: " + CoordinateRangeText());
    }
  }

  // Samples fill many lines (with comments between rows): a bad one is
  // reported at its own line, counted from <samples> through the text and
  // the comments, with its row and column. Stops at the first bad one.
  void ReadSamples() {
    const xmlNode* samples = xml::Child(node_, "samples");
    int line = xml::Line(samples);
    for (const xmlNode* part = samples ? samples->children : nullptr; part; part = part->next) {
      const std::string text = xml::RawText(part);
      if (part->type != XML_TEXT_NODE && part->type != XML_CDATA_SECTION_NODE) {
        line += static_cast<int>(std::count(text.begin(), text.end(), '\n'));
        continue;
      }
      if (!ReadSampleText(text, &line)) return;
    }
  }

  void CheckSampleCount(size_t errors_before) {
    const size_t expected = static_cast<size_t>(field_.rows) * static_cast<size_t>(field_.columns);
    if (reader_.ErrorCount() != errors_before || field_.samples.size() == expected) return;
    reader_.Error(xml::Child(node_, "samples"),
                  "heightfield has " + std::to_string(field_.samples.size()) +
                      " samples; rows x columns = " + std::to_string(field_.rows) + " x " +
                      std::to_string(field_.columns) + " needs " + std::to_string(expected));
  }

 private:
  int Count(const char* attribute) {
    const std::string text = xml::Attribute(node_, attribute).value_or("");
    char* end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || value < 2 || value > 100000) {
      reader_.Error(node_, std::string("heightfield ") + attribute + " '" + text +
                               "' must be a whole number from 2 to 100000");
      return 0;
    }
    return static_cast<int>(value);
  }

  double Positive(const char* tag) {
    const xmlNode* child = xml::Child(node_, tag);
    const auto v = reader_.Number(child, std::string("heightfield ") + tag);
    if (v && *v <= 0.0)
      reader_.Error(child, std::string("heightfield ") + tag + " must be positive, got " +
                               FormatNumber(*v, 10));
    return v.value_or(0.0);
  }

  // The white-space separated samples of one text node; *line follows its
  // line breaks. False after reporting a bad sample.
  bool ReadSampleText(const std::string& text, int* line) {
    for (size_t i = 0; i < text.size();) {
      if (std::isspace(static_cast<unsigned char>(text[i]))) {
        if (text[i++] == '\n') ++*line;
        continue;
      }
      const size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (!AddSample(text.substr(start, i - start), *line)) return false;
    }
    return true;
  }

  bool AddSample(const std::string& token, int line) {
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    const bool finite = *end == '\0' && std::isfinite(value);
    // The height ODE builds: offset + scale x sample, in the range of
    // every other coordinate.
    const double height = field_.offset + field_.scale * value;
    if (finite && std::abs(height) <= limits::kMaxCoordinate) {
      field_.samples.push_back(value);
      return true;
    }
    const std::string why =
        !finite ? std::string("is not a finite number")
                : "gives a height of " + FormatNumber(height, 10) +
                      " m (offset + scale x sample), out of range: |y| <= " +
                      FormatNumber(limits::kMaxCoordinate, 10) + " m";
    reader_.ErrorAt(SourceLocation{reader_.file(), line}, "samples",
                    "heightfield sample " + SamplePlace(field_.samples.size()) + " '" + token +
                        "' " + why);
    return false;
  }

  // "4 (row 2, column 2)" for the sample at index.
  std::string SamplePlace(size_t index) const {
    if (field_.columns <= 0) return std::to_string(index + 1);
    const size_t columns = static_cast<size_t>(field_.columns);
    return std::to_string(index + 1) + " (row " + std::to_string(index / columns + 1) +
           ", column " + std::to_string(index % columns + 1) + ")";
  }

  Reader& reader_;
  const xmlNode* node_;
  Heightfield& field_;
};

}  // namespace

std::optional<Heightfield> ReadHeightfield(Reader& reader, const xmlNode* node) {
  Heightfield field;
  field.where = reader.Where(node);
  field.material = xml::Attribute(node, "material").value_or("");
  const size_t errors_before = reader.ErrorCount();
  HeightfieldReading reading(reader, node, &field);
  reading.ReadGrid();
  reading.ReadPlacement();
  reading.ReadSamples();
  reading.CheckSampleCount(errors_before);
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return field;
}

}  // namespace simpartner::model::detail
