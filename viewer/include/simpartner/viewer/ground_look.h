// How a ground looks in the viewer and the camera: its colour by what
// its material is. A soil is drawn as what it is (sand, loam, clay, snow,
// lunar regolith), known by its soil's name (the library entry, or the
// material's when written out) and then the material's; rigid ground
// stays grey-green. Ruts are the ground's colour darkened (RutMesh). No
// GL here, so that it can be unit tested.
#pragma once

#include <array>
#include <string>

#include "simpartner/material_t.hpp"
#include "simpartner/model_t.hpp"

namespace simpartner::viewer {

enum class GroundKind { kRigid, kSand, kLoam, kClay, kSnow, kRegolith, kOtherSoil };

// What `material` is made of (kRigid when it is not a soil).
GroundKind GroundKindOf(const material_t& material);
// The material `name` of `model`, null when it has none of that name.
const material_t* FindMaterial(const model_t& model, const std::string& name);
// The kind of the ground whose material is `name` (kRigid without one).
GroundKind GroundKindOf(const model_t& model, const std::string& name);

// RGB 0..1: the ground's colour, and a heightfield's in its hollows
// (low) and on its tops (high).
std::array<float, 3> GroundColor(GroundKind kind);
std::array<float, 3> FieldLowColor(GroundKind kind);
std::array<float, 3> FieldHighColor(GroundKind kind);

}  // namespace simpartner::viewer
