#include "simpartner/viewer/ground_look.h"

#include <algorithm>
#include <cctype>

namespace simpartner::viewer {
namespace {

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The kind a name says, or kOtherSoil. A loam named sandy is loam; a
// clayey soil is clay.
GroundKind KindOfName(const std::string& name) {
  const std::string n = Lower(name);
  auto has = [&n](const char* word) { return n.find(word) != std::string::npos; };
  if (has("snow")) return GroundKind::kSnow;
  if (has("clay")) return GroundKind::kClay;
  if (has("loam")) return GroundKind::kLoam;
  if (has("sand")) return GroundKind::kSand;
  if (has("lunar") || has("regolith")) return GroundKind::kRegolith;
  return GroundKind::kOtherSoil;
}

std::array<float, 3> Scaled(const std::array<float, 3>& c, float by) {
  return {std::min(1.0f, c[0] * by), std::min(1.0f, c[1] * by), std::min(1.0f, c[2] * by)};
}

}  // namespace

GroundKind GroundKindOf(const material_t& material) {
  if (!material.is_soil) return GroundKind::kRigid;
  const GroundKind by_soil = KindOfName(material.soil_name);
  return by_soil != GroundKind::kOtherSoil ? by_soil : KindOfName(material.name);
}

const material_t* FindMaterial(const model_t& model, const std::string& name) {
  for (const material_t& m : model.materials)
    if (m.name == name) return &m;
  return nullptr;
}

GroundKind GroundKindOf(const model_t& model, const std::string& name) {
  const material_t* m = name.empty() ? nullptr : FindMaterial(model, name);
  return m == nullptr ? GroundKind::kRigid : GroundKindOf(*m);
}

std::array<float, 3> GroundColor(GroundKind kind) {
  switch (kind) {
    case GroundKind::kRigid: return {0.50f, 0.55f, 0.50f};
    case GroundKind::kSand: return {0.78f, 0.68f, 0.48f};
    case GroundKind::kLoam: return {0.45f, 0.35f, 0.25f};
    case GroundKind::kClay: return {0.62f, 0.40f, 0.27f};
    case GroundKind::kSnow: return {0.90f, 0.93f, 0.97f};
    case GroundKind::kRegolith: return {0.55f, 0.55f, 0.53f};
    case GroundKind::kOtherSoil: return {0.55f, 0.45f, 0.33f};
  }
  return {0.50f, 0.55f, 0.50f};
}

std::array<float, 3> FieldLowColor(GroundKind kind) {
  // Rigid terrain keeps the viewer's bluish grey hollows.
  if (kind == GroundKind::kRigid) return {0.60f, 0.66f, 0.75f};
  return Scaled(GroundColor(kind), 0.8f);
}

std::array<float, 3> FieldHighColor(GroundKind kind) {
  if (kind == GroundKind::kRigid) return {0.86f, 0.89f, 0.93f};
  return Scaled(GroundColor(kind), 1.1f);
}

}  // namespace simpartner::viewer
