// <material>: contact parameters, each within its range, and one way of
// giving the contact's softness.
#include "parts.h"
#include "simpartner/text.h"

namespace simpartner::model::detail {
namespace {

// One <material> being read; ok turns false at the first problem, and
// every problem is reported.
class MaterialReading {
 public:
  MaterialReading(Reader& reader, const xmlNode* node, const std::string& what)
      : reader_(reader), node_(node), what_(what) {}

  void ReadValues(Material* m) {
    m->mu = reader_.NumberOr(node_, "mu", m->mu, what_, &ok_);
    m->mu2 = OptionalNumber("mu2");
    ReadFrictionDirection(m);
    m->bounce = reader_.NumberOr(node_, "bounce", m->bounce, what_, &ok_);
    m->bounce_velocity = reader_.NumberOr(node_, "bounceVelocity", m->bounce_velocity, what_, &ok_);
    m->soft_erp = reader_.NumberOr(node_, "softERP", m->soft_erp, what_, &ok_);
    m->soft_cfm = reader_.NumberOr(node_, "softCFM", m->soft_cfm, what_, &ok_);
    m->stiffness = OptionalNumber("stiffness");
    m->damping = OptionalNumber("damping");
    m->rolling_friction =
        reader_.NumberOr(node_, "rollingFriction", m->rolling_friction, what_, &ok_);
  }

  void CheckRanges(const Material& m) {
    InRange(m.mu, 0.0, 1e6, "mu");
    if (m.mu2) InRange(*m.mu2, 0.0, 1e6, "mu2");
    InRange(m.bounce, 0.0, 1.0, "bounce");
    InRange(m.bounce_velocity, 0.0, 1e6, "bounceVelocity");
    InRange(m.soft_erp, 0.0, 1.0, "softERP");
    InRange(m.soft_cfm, 0.0, 1.0, "softCFM");
    InRange(m.rolling_friction, 0.0, 1.0, "rollingFriction");
    // A zero stiffness would make ERP 0: nothing holds the bodies apart.
    if (m.stiffness && (*m.stiffness <= 0.0 || *m.stiffness > limits::kMaxContactStiffness)) {
      Fail("stiffness", what_ + ": stiffness " + FormatNumber(*m.stiffness, 10) +
                            " N/m is out of range (0, " +
                            FormatNumber(limits::kMaxContactStiffness, 10) + "]");
    }
    if (m.damping) InRange(*m.damping, 0.0, limits::kMaxContactDamping, "damping");
  }

  // mu2 is read across a rolling direction: across a slip's own direction
  // it would act only while sticking, where a slip has none, and the old
  // reading held a slide from turning, which no Coulomb law does.
  void CheckAnisotropy(const Material& m) {
    if (!m.mu2 || *m.mu2 == m.mu || m.friction_direction != FrictionDirection::kSlip) return;
    Fail("mu2", what_ + ": mu2 " + FormatNumber(*m.mu2, 10) + " differs from mu " +
                    FormatNumber(m.mu, 10) +
                    " along the slip (frictionDirection slip, the default): friction across a "
                    "slip's own direction is not a Coulomb law; give frictionDirection rolling "
                    "(mu along a wheel's rolling direction, mu2 across it) or drop mu2 "
                    "(docs/contacts.md)");
  }

  // One softness, given one way: per step or physical.
  void CheckSoftness(const Material& m) {
    const bool per_step = xml::Child(node_, "softERP") || xml::Child(node_, "softCFM");
    const bool physical = m.stiffness || m.damping;
    const char* field = m.stiffness ? "stiffness" : "damping";
    if (per_step && physical) {
      Fail(field, what_ + ": stiffness/damping and softERP/softCFM both give the contact's "
                          "softness; give one of the two");
    } else if (m.stiffness.has_value() != m.damping.has_value()) {
      Fail(field, what_ + ": " +
                      (m.stiffness ? "stiffness without damping" : "damping without stiffness") +
                      "; give both (damping 0 for an undamped contact)");
    }
  }

  bool ok() const { return ok_; }

 private:
  std::optional<double> OptionalNumber(const char* field) {
    const xmlNode* child = xml::Child(node_, field);
    if (child == nullptr) return std::nullopt;
    const auto value = reader_.Number(child, what_ + " " + field);
    if (!value) ok_ = false;
    return value;
  }

  void ReadFrictionDirection(Material* m) {
    const xmlNode* d = xml::Child(node_, "frictionDirection");
    if (d == nullptr) return;
    const std::string text = xml::Text(d);
    if (text == ToString(FrictionDirection::kSlip)) {
      m->friction_direction = FrictionDirection::kSlip;
    } else if (text == ToString(FrictionDirection::kRolling)) {
      m->friction_direction = FrictionDirection::kRolling;
    } else {
      reader_.Error(d, what_ + ": frictionDirection '" + text + "' is not one of slip, rolling");
      ok_ = false;
    }
  }

  void InRange(double value, double lo, double hi, const char* field) {
    if (value >= lo && value <= hi) return;
    Fail(field, what_ + ": " + field + " " + FormatNumber(value, 10) + " is out of range [" +
                    FormatNumber(lo, 10) + ", " + FormatNumber(hi, 10) + "]");
  }

  // A problem at the field's element, or at the material when it is absent.
  void Fail(const char* field, const std::string& message) {
    const xmlNode* child = xml::Child(node_, field);
    reader_.Error(child != nullptr ? child : node_, message);
    ok_ = false;
  }

  Reader& reader_;
  const xmlNode* node_;
  const std::string what_;
  bool ok_ = true;
};

}  // namespace

std::optional<Material> ReadMaterial(Reader& reader, const xmlNode* node,
                                     SoilLibraries* soils) {
  Material m;
  m.name = xml::Attribute(node, "name").value_or("");
  m.where = reader.Where(node);
  MaterialReading reading(reader, node, "material '" + m.name + "'");
  reading.ReadValues(&m);
  reading.CheckRanges(m);
  if (reading.ok()) reading.CheckAnisotropy(m);
  reading.CheckSoftness(m);
  bool soil_ok = true;
  if (const xmlNode* soil = xml::Child(node, "soil"); soil != nullptr && soils != nullptr) {
    m.soil = ReadSoil(reader, soil, m.name, soils);
    soil_ok = m.soil.has_value();
  }
  if (!reading.ok() || !soil_ok) return std::nullopt;
  return m;
}

}  // namespace simpartner::model::detail
