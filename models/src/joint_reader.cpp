// <joint>: the two bodies it joins, its anchor, axes and limits.
#include <cmath>
#include <cstdlib>

#include "parts.h"
#include "simpartner/text.h"

namespace simpartner::model::detail {
namespace {

JointKind ParseJointKind(const std::string& type) {
  if (type == "Hinge") return JointKind::kHinge;
  if (type == "Slider") return JointKind::kSlider;
  if (type == "Ball") return JointKind::kBall;
  if (type == "Universal") return JointKind::kUniversal;
  if (type == "Hinge2") return JointKind::kHinge2;
  return JointKind::kFixed;
}

class JointReading {
 public:
  JointReading(Reader& reader, const xmlNode* node, Joint* joint)
      : reader_(reader), node_(node), joint_(*joint), what_("joint '" + joint->name + "'") {}

  void ReadBodies(const std::function<bool(const std::string&)>& body_exists,
                  const std::string& owner) {
    const xmlNode* b1 = xml::Child(node_, "body1");
    const xmlNode* b2 = xml::Child(node_, "body2");
    joint_.body1 = xml::Text(b1);
    joint_.body2 = xml::Text(b2);
    if (!body_exists(joint_.body1))
      reader_.Error(b1, what_ + ": body1 '" + joint_.body1 + "' is not a body of " + owner);
    if (!body_exists(joint_.body2))
      reader_.Error(b2, what_ + ": body2 '" + joint_.body2 + "' is not a body of " + owner);
    if (joint_.body1 == joint_.body2)
      reader_.Error(b2, what_ + ": joins body '" + joint_.body1 +
                            "' to itself (a joint joins exactly two bodies)");
  }

  void ReadAnchor() {
    const xmlNode* anchor = xml::Child(node_, "anchor");
    if (anchor == nullptr) {
      if (joint_.kind != JointKind::kFixed && joint_.kind != JointKind::kSlider)
        reader_.Error(node_, what_ + ": a " + ToString(joint_.kind) + " joint needs <anchor>");
      return;
    }
    const auto a = reader_.Vector(anchor, what_ + " anchor");
    if (!a) return;
    joint_.anchor = *a;
    if (!CoordinatesInRange(*a))
      reader_.Error(anchor, what_ + ": anchor " + VectorText(*a) + " m is out of range: " +
                                CoordinateRangeText());
  }

  // As many axes as the kind has, none beyond; two must not be parallel.
  void ReadAxes(size_t errors_before) {
    const int axes = AxisCount(joint_.kind);
    const char* tags[2] = {"axis1", "axis2"};
    for (int i = 0; i < 2; ++i) {
      const xmlNode* axis = xml::Child(node_, tags[i]);
      if (i < axes) {
        ReadAxis(axis, tags[i], &joint_.axis[i]);
      } else if (axis != nullptr) {
        reader_.Error(axis, what_ + ": a " + ToString(joint_.kind) + " joint has no <" + tags[i] + ">");
      }
    }
    if (axes == 2 && reader_.ErrorCount() == errors_before &&
        std::abs(joint_.axis[0].dot(joint_.axis[1])) > 1.0 - 1e-6) {
      reader_.Error(xml::Child(node_, "axis2"), what_ + ": axis1 and axis2 are parallel");
    }
  }

  void ReadLimits() {
    for (const xmlNode* limits : xml::Children(node_, "limits")) ReadLimit(limits);
  }

 private:
  void ReadAxis(const xmlNode* axis, const char* tag, Eigen::Vector3d* out) {
    if (axis == nullptr) {
      reader_.Error(node_, what_ + ": a " + ToString(joint_.kind) + " joint needs <" + tag + ">");
      return;
    }
    const auto a = reader_.Vector(axis, what_ + " " + tag);
    if (!a) return;
    if (a->norm() < 1e-9)
      reader_.Error(axis, what_ + ": " + tag + " has zero length");
    else
      *out = a->normalized();
  }

  void ReadLimit(const xmlNode* limits) {
    const int axis = std::atoi(xml::Attribute(limits, "axis").value_or("1").c_str());
    if (axis < 1 || axis > AxisCount(joint_.kind)) {
      reader_.Error(limits, what_ + ": a " + ToString(joint_.kind) + " joint has no axis " +
                                std::to_string(axis) + " to limit");
      return;
    }
    const auto lo = reader_.Number(xml::Child(limits, "lo"), what_ + " limits lo");
    const auto hi = reader_.Number(xml::Child(limits, "hi"), what_ + " limits hi");
    if (!lo || !hi) return;
    if (*lo > *hi) {
      reader_.Error(limits, what_ + ": limits lo " + FormatNumber(*lo, 10) + " > hi " +
                                FormatNumber(*hi, 10));
      return;
    }
    // ODE's angular stops only work within [-pi, pi].
    const bool angular = joint_.kind != JointKind::kSlider;
    if (angular && (*lo < -M_PI || *hi > M_PI)) {
      reader_.Error(limits, what_ + ": angular limits [" + FormatNumber(*lo, 10) + ", " +
                                FormatNumber(*hi, 10) + "] must lie within [-pi, pi]");
      return;
    }
    joint_.lo_stop[axis - 1] = *lo;
    joint_.hi_stop[axis - 1] = *hi;
  }

  Reader& reader_;
  const xmlNode* node_;
  Joint& joint_;
  const std::string what_;
};

}  // namespace

std::optional<Joint> ReadJoint(Reader& reader, const xmlNode* node,
                               const std::function<bool(const std::string&)>& body_exists,
                               const std::string& owner) {
  Joint joint;
  joint.name = xml::Attribute(node, "name").value_or("");
  joint.kind = ParseJointKind(xml::Attribute(node, "type").value_or("Fixed"));
  joint.where = reader.Where(node);
  const size_t errors_before = reader.ErrorCount();
  JointReading reading(reader, node, &joint);
  reading.ReadBodies(body_exists, owner);
  reading.ReadAnchor();
  reading.ReadAxes(errors_before);
  reading.ReadLimits();
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return joint;
}

}  // namespace simpartner::model::detail
