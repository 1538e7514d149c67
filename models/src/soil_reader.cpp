// A soil's figures (docs/soil.md), read from the children of a library
// entry or of a world's <soil>, and each checked against its physical
// range; a world's <soil>: a library entry with overrides, or written out.
#include "parts.h"
#include "simpartner/edit_distance.h"
#include "simpartner/text.h"

namespace simpartner::model::detail {
namespace {

// One figure: its element (world.dtd and soils.dtd share the names), where
// it goes and its unit for messages.
struct SoilField {
  const char* element;
  double SoilParameters::*member;
  const char* unit;
};

constexpr SoilField kSoilFields[] = {
    {"n", &SoilParameters::n, ""},
    {"kc", &SoilParameters::k_c, " kN/m^(n+1)"},
    {"kphi", &SoilParameters::k_phi, " kN/m^(n+2)"},
    {"cohesion", &SoilParameters::cohesion, " kPa"},
    {"frictionAngle", &SoilParameters::friction_angle, " deg"},
    {"shearModulus", &SoilParameters::shear_modulus, " m"},
    {"unloadingStiffness", &SoilParameters::unloading_stiffness, " kPa/m"},
    {"viscosity", &SoilParameters::viscosity, " kPa s/m"},
};

const SoilField& FieldOf(const char* element) {
  for (const SoilField& f : kSoilFields)
    if (std::string(f.element) == element) return f;
  return kSoilFields[0];  // unreachable: callers name fields of the table
}

// The checks of one soil; each problem at its figure's element when node
// has it (else at node), naming the figure and its value.
class SoilRangeCheck {
 public:
  SoilRangeCheck(Reader& reader, const xmlNode* node, const std::string& what,
                 const SoilParameters& soil)
      : reader_(reader), node_(node), what_(what), soil_(soil) {}

  bool Run() {
    Require("n", soil_.n > 0.0, "must be > 0 (the sinkage exponent)");
    Require("kc", soil_.k_c >= 0.0, "must be >= 0");
    Require("kphi", soil_.k_phi >= 0.0, "must be >= 0");
    if (soil_.k_c == 0.0 && soil_.k_phi == 0.0)
      Fail("kc", what_ + ": kc and kphi are both 0: the soil would bear no load");
    Require("cohesion", soil_.cohesion >= 0.0, "must be >= 0");
    Require("frictionAngle", soil_.friction_angle >= 0.0 && soil_.friction_angle < 90.0,
            "must be >= 0 and < 90");
    Require("shearModulus", soil_.shear_modulus > 0.0,
            "must be > 0 (Janosi and Hanamoto's K: a length)");
    Require("unloadingStiffness", soil_.unloading_stiffness > 0.0, "must be > 0");
    Require("viscosity", soil_.viscosity >= 0.0, "must be >= 0");
    return ok_;
  }

 private:
  void Require(const char* element, bool good, const char* rule) {
    if (good) return;
    const SoilField& f = FieldOf(element);
    Fail(element, what_ + ": " + element + " " + FormatNumber(soil_.*f.member, 10) + f.unit +
                      " is out of range: " + rule);
  }

  void Fail(const char* element, const std::string& message) {
    const xmlNode* child = xml::Child(node_, element);
    reader_.Error(child != nullptr ? child : node_, message);
    ok_ = false;
  }

  Reader& reader_;
  const xmlNode* node_;
  const std::string& what_;
  const SoilParameters& soil_;
  bool ok_ = true;
};

// A <soil library=... name=...>: the entry, then the figures the world
// gives in its place.
std::optional<SoilParameters> ReadLibrarySoil(Reader& reader, const xmlNode* node,
                                              const std::string& what,
                                              const std::string& library_name,
                                              SoilLibraries* libraries) {
  const std::optional<std::string> entry = xml::Attribute(node, "name");
  if (!entry) {
    reader.Error(node, what + ": library '" + library_name +
                           "' without name=: say which of its soils");
    return std::nullopt;
  }
  std::string why;
  const SoilLibrary* library = libraries->Get(reader.file(), library_name, &why);
  if (library == nullptr) {
    reader.Error(node, what + ": cannot use soil library '" + library_name + "' (" + why + ")");
    return std::nullopt;
  }
  const SoilParameters* found = library->Find(*entry);
  if (found == nullptr) {
    std::vector<std::string> names;
    for (const SoilParameters& s : library->soils) names.push_back(s.name);
    const std::string near = NearestName(*entry, names);
    reader.Error(node, what + ": soil library '" + library_name + "' has no soil '" + *entry +
                           "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                           "; it has " + library->Names());
    return std::nullopt;
  }
  SoilParameters soil = *found;
  std::vector<std::string> given;
  if (!ReadSoilFigures(reader, node, what, &soil, &given)) return std::nullopt;
  if (!given.empty()) {
    std::string list;
    for (const std::string& g : given) list += (list.empty() ? "" : ", ") + g;
    soil.source += "; " + list + " given by " + reader.file() + ":" +
                   std::to_string(xml::Line(node)) + " instead";
  }
  return soil;
}

// A <soil> written out: every figure, named after its material.
std::optional<SoilParameters> ReadInlineSoil(Reader& reader, const xmlNode* node,
                                             const std::string& what,
                                             const std::string& material_name) {
  if (const auto entry = xml::Attribute(node, "name")) {
    reader.Error(node, what + ": name '" + *entry +
                           "' without library=: name picks an entry of a soil library");
    return std::nullopt;
  }
  SoilParameters soil;
  soil.name = material_name;
  soil.source = "written out at " + reader.file() + ":" + std::to_string(xml::Line(node));
  std::vector<std::string> given;
  if (!ReadSoilFigures(reader, node, what, &soil, &given)) return std::nullopt;
  std::string missing;
  for (const SoilField& f : kSoilFields) {
    if (xml::Child(node, f.element) == nullptr)
      missing += std::string(missing.empty() ? "" : ", ") + f.element;
  }
  if (!missing.empty()) {
    reader.Error(node, what + ": lacks " + missing +
                           "; a soil without library= gives every figure (n, kc, kphi, "
                           "cohesion, frictionAngle, shearModulus, unloadingStiffness, "
                           "viscosity)");
    return std::nullopt;
  }
  return soil;
}

}  // namespace

bool ReadSoilFigures(Reader& reader, const xmlNode* node, const std::string& what,
                     SoilParameters* soil, std::vector<std::string>* given) {
  bool ok = true;
  for (const SoilField& f : kSoilFields) {
    const xmlNode* child = xml::Child(node, f.element);
    if (child == nullptr) continue;
    const std::optional<double> value = reader.Number(child, what + " " + f.element);
    if (!value) {
      ok = false;
      continue;
    }
    soil->*f.member = *value;
    given->push_back(f.element);
  }
  return ok;
}

bool CheckSoilRanges(Reader& reader, const xmlNode* node, const std::string& what,
                     const SoilParameters& soil) {
  return SoilRangeCheck(reader, node, what, soil).Run();
}

std::optional<SoilParameters> ReadSoil(Reader& reader, const xmlNode* node,
                                       const std::string& material_name,
                                       SoilLibraries* libraries) {
  const std::string what = "material '" + material_name + "' soil";
  const std::optional<std::string> library = xml::Attribute(node, "library");
  std::optional<SoilParameters> soil =
      library ? ReadLibrarySoil(reader, node, what, *library, libraries)
              : ReadInlineSoil(reader, node, what, material_name);
  if (!soil || !CheckSoilRanges(reader, node, what, *soil)) return std::nullopt;
  soil->where = reader.Where(node);
  return soil;
}

}  // namespace simpartner::model::detail
