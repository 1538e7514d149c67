// A ground is drawn in its material's colour: each soil of the library by
// what it is, a soil written out by its material's name, rigid ground in
// the viewer's grey-green; the kinds' colours differ from one another.
#include <gtest/gtest.h>

#include <set>

#include "simpartner/viewer/ground_look.h"

namespace simpartner::viewer {
namespace {

material_t Soil(const std::string& material, const std::string& soil) {
  material_t m{};
  m.name = material;
  m.is_soil = true;
  m.soil_name = soil;
  return m;
}

TEST(GroundLook, EachSoilOfTheLibraryIsWhatItsNameSays) {
  EXPECT_EQ(GroundKindOf(Soil("ground", "dry_sand")), GroundKind::kSand);
  EXPECT_EQ(GroundKindOf(Soil("ground", "sandy_loam")), GroundKind::kLoam);
  EXPECT_EQ(GroundKindOf(Soil("ground", "clayey_soil")), GroundKind::kClay);
  EXPECT_EQ(GroundKindOf(Soil("ground", "heavy_clay")), GroundKind::kClay);
  EXPECT_EQ(GroundKindOf(Soil("ground", "snow_sweden")), GroundKind::kSnow);
  EXPECT_EQ(GroundKindOf(Soil("ground", "lunar_nominal")), GroundKind::kRegolith);
}

TEST(GroundLook, ASoilWrittenOutGoesByItsMaterialsName) {
  // Written out, the soil takes the material's name.
  EXPECT_EQ(GroundKindOf(Soil("Snow", "Snow")), GroundKind::kSnow);
  EXPECT_EQ(GroundKindOf(Soil("my_mud", "my_mud")), GroundKind::kOtherSoil);
  material_t ice{};
  ice.name = "snowy_ice";  // not a soil: rigid, whatever its name
  EXPECT_EQ(GroundKindOf(ice), GroundKind::kRigid);
}

TEST(GroundLook, TheModelsGroundMaterialDecides) {
  model_t m{};
  m.materials = {Soil("sand", "dry_sand")};
  m.num_materials = 1;
  EXPECT_EQ(GroundKindOf(m, "sand"), GroundKind::kSand);
  EXPECT_EQ(GroundKindOf(m, ""), GroundKind::kRigid);
  EXPECT_EQ(GroundKindOf(m, "missing"), GroundKind::kRigid);
}

TEST(GroundLook, EveryKindHasItsOwnColourAndAFieldIsDarkerInItsHollows) {
  std::set<std::array<float, 3>> colours;
  for (GroundKind kind : {GroundKind::kRigid, GroundKind::kSand, GroundKind::kLoam,
                          GroundKind::kClay, GroundKind::kSnow, GroundKind::kRegolith,
                          GroundKind::kOtherSoil}) {
    colours.insert(GroundColor(kind));
    const auto low = FieldLowColor(kind), high = FieldHighColor(kind);
    EXPECT_LT(low[0] + low[1] + low[2], high[0] + high[1] + high[2]);
  }
  EXPECT_EQ(colours.size(), 7u);
}

}  // namespace
}  // namespace simpartner::viewer
