// A soil's figures (docs/soil.md), read from the children of a library
// entry or of a world's <soil>, and each checked against its physical
// range; a world's <soil>: a library entry with overrides, or written out.
#include "parts.h"
#include "simpartner/edit_distance.h"
#include "simpartner/text.h"

namespace simpartner::model::detail {
namespace {

// One figure: its element (world.dtd and soils.dtd share the names), where
// it goes, its unit for messages, and its physical range [lo, hi] (lo
// itself refused when lo_open). The ranges hold the soils of Wong's Table
// 2.3 (models/soils/wong2008.xml and LETE sand) with room to spare; what
// lies beyond is a typing error (n 1e6 makes every soil bear nothing at a
// centimetre, K 1e-300 a step in traction no step size resolves).
struct SoilField {
  const char* element;
  double SoilParameters::*member;
  const char* unit;
  double lo;
  bool lo_open;
  double hi;
  const char* measured;  // what measured soils have, for the message
  bool optional = false;  // a file may leave it out (then 0)
};

constexpr SoilField kSoilFields[] = {
    {"n", &SoilParameters::n, "", 0.0, true, 3.0,
     "the sinkage exponent; Wong's Table 2.3: 0.13 to 1.6"},
    {"kc", &SoilParameters::k_c, " kN/m^(n+1)", 0.0, false, 1e4, "Table 2.3: 0.99 to 102"},
    {"kphi", &SoilParameters::k_phi, " kN/m^(n+2)", 0.0, false, 1e5,
     "Table 2.3: 66 to 5,301"},
    {"cohesion", &SoilParameters::cohesion, " kPa", 0.0, false, 1000.0,
     "Table 2.3: 1.03 to 68.95"},
    {"frictionAngle", &SoilParameters::friction_angle, " deg", 0.0, false, 60.0,
     "Table 2.3: 13 to 34"},
    {"shearModulus", &SoilParameters::shear_modulus, " m", 5e-4, false, 1.0,
     "Janosi and Hanamoto's K, a length; Wong's typical values 0.006 to 0.025 m"},
    {"unloadingStiffness", &SoilParameters::unloading_stiffness, " kPa/m", 0.0, false, 1e6,
     "Wong's k_0 in k_u = k_0 + A_u z_max; 0 for LETE sand"},
    {"unloadingGrowth", &SoilParameters::unloading_growth, " kPa/m^2", 0.0, false, 1e8,
     "Wong's A_u in k_u = k_0 + A_u z_max; about 503,000 for LETE sand", true},
    {"viscosity", &SoilParameters::viscosity, " kPa s/m", 0.0, false, 1e4,
     "1e4 is 1 MPa at 0.1 m/s"},
};

// The checks of one soil; each problem at its figure's element when node
// has it (else at node), naming the figure, its value and its range.
class SoilRangeCheck {
 public:
  SoilRangeCheck(Reader& reader, const xmlNode* node, const std::string& what,
                 const SoilParameters& soil)
      : reader_(reader), node_(node), what_(what), soil_(soil) {}

  bool Run() {
    for (const SoilField& f : kSoilFields) CheckRange(f);
    if (soil_.k_c == 0.0 && soil_.k_phi == 0.0)
      Fail("kc", what_ + ": kc and kphi are both 0: the soil would bear no load");
    return ok_;
  }

 private:
  void CheckRange(const SoilField& f) {
    const double v = soil_.*f.member;
    if ((f.lo_open ? v > f.lo : v >= f.lo) && v <= f.hi) return;
    Fail(f.element, what_ + ": " + f.element + " " + FormatNumber(v, 10) + f.unit +
                        " is out of range " + (f.lo_open ? "(" : "[") + FormatNumber(f.lo, 10) +
                        ", " + FormatNumber(f.hi, 10) + "]" + f.unit + " (" + f.measured +
                        ")");
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
    if (!f.optional && xml::Child(node, f.element) == nullptr)
      missing += std::string(missing.empty() ? "" : ", ") + f.element;
  }
  if (!missing.empty()) {
    reader.Error(node, what + ": lacks " + missing +
                           "; a soil without library= gives every figure (n, kc, kphi, "
                           "cohesion, frictionAngle, shearModulus, unloadingStiffness, "
                           "viscosity; unloadingGrowth may be left out)");
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
