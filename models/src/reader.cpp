#include "reader.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "simpartner/text.h"

namespace simpartner::model::detail {
namespace {

// Files written with three decimals (0.707 for cos 45 deg) must load: their
// |R^T R - I| is 3e-4. Two decimals (0.71: 8e-3) or any real shear fail.
constexpr double kOrthonormalTolerance = 2e-3;

}  // namespace

std::optional<double> Reader::Number(const xmlNode* node, const std::string& what) {
  if (node == nullptr) return std::nullopt;
  const std::string text = xml::Text(node);
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0') {
    Error(node, what + ": '" + text + "' is not a number");
    return std::nullopt;
  }
  if (!std::isfinite(value)) {
    Error(node, what + ": '" + text + "' is not a finite number");
    return std::nullopt;
  }
  return value;
}

double Reader::NumberOr(const xmlNode* parent, const char* name, double fallback,
                        const std::string& what, bool* ok) {
  const xmlNode* child = xml::Child(parent, name);
  if (child == nullptr) return fallback;
  const auto value = Number(child, what + " " + name);
  if (!value) {
    *ok = false;
    return fallback;
  }
  return *value;
}

std::optional<Eigen::Vector3d> Reader::Vector(const xmlNode* node, const char* cx, const char* cy,
                                              const char* cz, const std::string& what) {
  if (node == nullptr) return std::nullopt;
  const auto x = Number(xml::Child(node, cx), what + " " + cx);
  const auto y = Number(xml::Child(node, cy), what + " " + cy);
  const auto z = Number(xml::Child(node, cz), what + " " + cz);
  if (!x || !y || !z) return std::nullopt;
  return Eigen::Vector3d(*x, *y, *z);
}

std::optional<Eigen::Isometry3d> Reader::Transformation(const xmlNode* node,
                                                        const std::string& what) {
  if (node == nullptr) return std::nullopt;
  Eigen::Matrix<double, 3, 4> t;
  bool ok = true;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      const std::string tag = "T" + std::to_string(r) + std::to_string(c);
      const auto value = Number(xml::Child(node, tag.c_str()), what + " " + tag);
      if (!value) {
        ok = false;
        continue;
      }
      t(r, c) = *value;
    }
  }
  if (!ok) return std::nullopt;
  const Eigen::Matrix3d rotation = t.leftCols<3>();
  const double error = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity())
                           .cwiseAbs().maxCoeff();
  if (error > kOrthonormalTolerance || rotation.determinant() < 0) {
    std::ostringstream message;
    message << what << ": rotation part T00..T22 is not a rotation matrix "
            << "(|R^T R - I| = " << FormatNumber(error, 10) << ", det = "
            << FormatNumber(rotation.determinant(), 10) << ")";
    Error(node, message.str());
    return std::nullopt;
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(rotation).normalized().toRotationMatrix();
  pose.translation() = t.col(3);
  return pose;
}

std::string Range(double lo, double hi, const char* unit) {
  return "[" + FormatNumber(lo, 10) + ", " + FormatNumber(hi, 10) + "]" + unit;
}

std::string VectorText(const Eigen::Vector3d& v) {
  return "(" + FormatNumber(v.x(), 10) + ", " + FormatNumber(v.y(), 10) + ", " +
         FormatNumber(v.z(), 10) + ")";
}

bool CoordinatesInRange(const Eigen::Vector3d& p) {
  return p.cwiseAbs().maxCoeff() <= limits::kMaxCoordinate;
}

std::string CoordinateRangeText() {
  return "|x|, |y|, |z| <= " + FormatNumber(limits::kMaxCoordinate, 10) + " m";
}

}  // namespace simpartner::model::detail
