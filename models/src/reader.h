// The loader's walk over a validated document (internal to sp_model): a
// Reader turns element text into numbers, vectors and poses, and reports
// every problem at its element's file and line; the text helpers write
// values into messages the same way everywhere.
#pragma once

#include <Eigen/Geometry>

#include <optional>
#include <string>

#include "simpartner/diagnostic.h"
#include "simpartner/model/model.h"
#include "simpartner/xml_document.h"

namespace simpartner::model::detail {

// The name a joint of the world uses for the static world itself.
inline constexpr const char* kWorldBodyName = "world";

class Reader {
 public:
  Reader(std::string file_name, DiagnosticList* diagnostics)
      : file_(std::move(file_name)), diagnostics_(diagnostics) {}

  const std::string& file() const { return file_; }
  SourceLocation Where(const xmlNode* node) const { return SourceLocation{file_, xml::Line(node)}; }
  void Error(const xmlNode* node, const std::string& message) {
    xml::AddAt(diagnostics_, file_, node, message);
  }
  void ErrorAt(const SourceLocation& where, const std::string& element,
               const std::string& message) {
    diagnostics_->Add(where.file, where.line, element, message);
  }
  size_t ErrorCount() const { return diagnostics_->size(); }

  // A finite number from the element's text; reports and returns nullopt
  // otherwise. what names the quantity for the message.
  std::optional<double> Number(const xmlNode* node, const std::string& what);
  // Number of child `name`, or fallback when the child is absent; a bad
  // one is reported, sets *ok to false and gives fallback.
  double NumberOr(const xmlNode* parent, const char* name, double fallback,
                  const std::string& what, bool* ok);
  // Children cx, cy, cz (x, y, z) of node as a vector.
  std::optional<Eigen::Vector3d> Vector(const xmlNode* node, const char* cx, const char* cy,
                                        const char* cz, const std::string& what);
  std::optional<Eigen::Vector3d> Vector(const xmlNode* node, const std::string& what) {
    return Vector(node, "x", "y", "z", what);
  }
  // The original's 3x4 transformation (T00..T23); the rotation part must
  // be a proper rotation within a tolerance and is re-orthonormalised, so
  // that rounded values in files do not shear bodies.
  std::optional<Eigen::Isometry3d> Transformation(const xmlNode* node, const std::string& what);

 private:
  std::string file_;
  DiagnosticList* diagnostics_;
};

// "[lo, hi] unit"
std::string Range(double lo, double hi, const char* unit);
// "(x, y, z)"
std::string VectorText(const Eigen::Vector3d& v);
// True when every coordinate of p is within limits::kMaxCoordinate.
bool CoordinatesInRange(const Eigen::Vector3d& p);
// "|x|, |y|, |z| <= 1e+06 m"
std::string CoordinateRangeText();

}  // namespace simpartner::model::detail
