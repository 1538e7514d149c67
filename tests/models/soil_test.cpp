// Soils (docs/soil.md): the shipped library holds Wong's Table 2.3 rows as
// printed; a world's material takes an entry, changes single figures, or
// writes a soil out; every bad figure, name, library or use is refused at
// its file and line. Expected figures are typed from the sources, never
// read from the loader; lines are found in the XML text by a marker.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "model_test_support.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/model_message.h"
#include "simpartner/model/soil_library.h"

namespace simpartner::model {
namespace {

using testing::LineOf;
using testing::Pose;

const std::string kSource = SP_SOURCE_DIR;
const std::string kShippedLibrary = kSource + "/models/soils/wong2008.xml";
// A world beside the shipped ones: "../soils/wong2008.xml" is the library.
const std::string kWorldFile = kSource + "/models/worlds/soil_test.xml";

// Every figure of an inline <soil>, each on one line; replace one with
// Swap to make it wrong.
const std::string kInlineSoil =
    "<soil>\n<n>1.1</n>\n<kc>0.99</kc>\n<kphi>1528.43</kphi>\n<cohesion>1.04</cohesion>\n"
    "<frictionAngle>28</frictionAngle>\n<shearModulus>0.025</shearModulus>\n"
    "<unloadingStiffness>10000</unloadingStiffness>\n<viscosity>0</viscosity>\n</soil>";

std::string Swap(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// A world whose surface has the material "ground" with the given soil.
std::string WorldWithSoil(const std::string& soil) {
  return "<world>\n<surface material=\"ground\"><a>0</a><b>1</b><c>0</c><d>0</d></surface>\n"
         "<material name=\"ground\"><mu>0.8</mu>\n" +
         soil + "\n</material>\n</world>";
}

// Files served from memory; anything else cannot be read.
FileReader Serve(const std::map<std::string, std::string>& files) {
  return [files](const std::string& path, std::string* out) {
    const auto it = files.find(path);
    if (it == files.end()) return false;
    *out = it->second;
    return true;
  };
}

// The one diagnostic of a refused world at file:line of marker, with words.
void ExpectRefused(const WorldLoadResult& result, const std::string& xml, const std::string& file,
                   const std::string& marker, const std::vector<std::string>& words) {
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.file, file);
  EXPECT_EQ(d.line, LineOf(xml, marker)) << d.message;
  for (const std::string& word : words)
    EXPECT_NE(d.message.find(word), std::string::npos) << "'" << word << "' not in: " << d.message;
}

void ExpectInlineRefused(const std::string& soil, const std::string& marker,
                         const std::vector<std::string>& words) {
  const std::string xml = WorldWithSoil(soil);
  ExpectRefused(ParseWorld(xml, "soil.xml"), xml, "soil.xml", marker, words);
}

struct Row {
  const char* name;
  double n, kc, kphi, c, phi, K;
};

// Wong (2008) Table 2.3 (n, kc, kphi, c, phi), K from Wong's text; the
// Lunar Sourcebook's nominal soil.
const Row kExpected[] = {
    {"dry_sand", 1.1, 0.99, 1528.43, 1.04, 28, 0.025},
    {"sandy_loam", 0.7, 5.27, 1515.04, 1.72, 29, 0.025},
    {"clayey_soil", 0.5, 13.19, 692.15, 4.14, 13, 0.006},
    {"heavy_clay", 0.13, 12.70, 1555.95, 68.95, 34, 0.006},
    {"snow", 1.6, 4.37, 196.72, 1.03, 19.7, 0.025},
    {"snow_sweden", 1.44, 10.55, 66.08, 6, 20.7, 0.025},
    {"lunar_nominal", 1, 1.4, 820, 0.17, 35, 0.018},
};

TEST(SoilLibrary, TheShippedLibraryHasTheTablesFigures) {
  const SoilLibraryLoadResult result = LoadSoilLibraryFile(kShippedLibrary);
  ASSERT_TRUE(result.library) << result.diagnostics.Format();
  ASSERT_EQ(result.library->soils.size(), std::size(kExpected));
  for (const Row& row : kExpected) {
    SCOPED_TRACE(row.name);
    const SoilParameters* s = result.library->Find(row.name);
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->n, row.n);
    EXPECT_EQ(s->k_c, row.kc);
    EXPECT_EQ(s->k_phi, row.kphi);
    EXPECT_EQ(s->cohesion, row.c);
    EXPECT_EQ(s->friction_angle, row.phi);
    EXPECT_EQ(s->shear_modulus, row.K);
    EXPECT_EQ(s->unloading_stiffness, 0.0);  // LETE sand's k_0 and A_u, assumed
    EXPECT_EQ(s->unloading_growth, 503000.0);
    EXPECT_EQ(s->viscosity, 0.0);
    const bool lunar = std::string(row.name) == "lunar_nominal";
    EXPECT_NE(s->source.find(lunar ? "Lunar Sourcebook" : "Table 2.3"), std::string::npos)
        << s->source;
    EXPECT_EQ(s->where.file, kShippedLibrary);
    EXPECT_GT(s->where.line, 0);
  }
}

TEST(SoilLibrary, AWorldTakesAnEntryBesideTheShippedWorlds) {
  const WorldLoadResult result = ParseWorld(
      WorldWithSoil("<soil library=\"../soils/wong2008.xml\" name=\"snow\"/>"), kWorldFile);
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const Material* ground = result.world->FindMaterial("ground");
  ASSERT_NE(ground, nullptr);
  ASSERT_TRUE(ground->soil);
  EXPECT_EQ(ground->soil->name, "snow");
  EXPECT_EQ(ground->soil->n, 1.6);
  EXPECT_EQ(ground->soil->k_phi, 196.72);
  EXPECT_EQ(ground->mu, 0.8);  // the material's own figures stay
  EXPECT_EQ(ground->soil->where.file, kWorldFile);
  EXPECT_EQ(ground->soil->where.line, 4);  // the world's <soil>, not the library's entry
}

// As for robots: a world away from models/worlds finds the shipped
// library under the data roots, and a missing one names where it looked.
TEST(SoilLibrary, AWorldElsewhereFindsTheShippedLibrary) {
  const std::string elsewhere = "/sp_nowhere/worlds/soil.xml";
  const WorldLoadResult found = ParseWorld(
      WorldWithSoil("<soil library=\"../soils/wong2008.xml\" name=\"heavy_clay\"/>"), elsewhere);
  ASSERT_TRUE(found.world) << found.diagnostics.Format();
  EXPECT_EQ(found.world->FindMaterial("ground")->soil->cohesion, 68.95);
  const WorldLoadResult missing = ParseWorld(
      WorldWithSoil("<soil library=\"../soils/wong1999.xml\" name=\"heavy_clay\"/>"), elsewhere);
  EXPECT_FALSE(missing.world);
  EXPECT_NE(missing.diagnostics.Format().find("also looked for it at " + kSource +
                                              "/models/soils/wong1999.xml (source tree)"),
            std::string::npos)
      << missing.diagnostics.Format();
}

TEST(SoilLibrary, AFigureGivenInTheWorldReplacesTheEntrys) {
  const WorldLoadResult result = ParseWorld(
      WorldWithSoil("<soil library=\"../soils/wong2008.xml\" name=\"dry_sand\">"
                    "<kphi>1600</kphi><viscosity>5</viscosity></soil>"),
      kWorldFile);
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const SoilParameters& soil = *result.world->FindMaterial("ground")->soil;
  EXPECT_EQ(soil.k_phi, 1600.0);
  EXPECT_EQ(soil.viscosity, 5.0);
  EXPECT_EQ(soil.n, 1.1);  // the rest as the library has it
  EXPECT_EQ(soil.k_c, 0.99);
  EXPECT_EQ(soil.friction_angle, 28.0);
  EXPECT_NE(soil.source.find("kphi, viscosity given by " + kWorldFile + ":4"), std::string::npos)
      << soil.source;
}

TEST(SoilLibrary, ASoilWrittenOutIsNamedAfterItsMaterial) {
  const std::string soil =
      Swap(Swap(kInlineSoil, "<n>1.1</n>", "<n>0.8</n>"), "<viscosity>0<", "<viscosity>2.5<");
  const WorldLoadResult result = ParseWorld(WorldWithSoil(soil), "soil.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const SoilParameters& s = *result.world->FindMaterial("ground")->soil;
  EXPECT_EQ(s.name, "ground");
  EXPECT_EQ(s.n, 0.8);
  EXPECT_EQ(s.k_c, 0.99);
  EXPECT_EQ(s.k_phi, 1528.43);
  EXPECT_EQ(s.cohesion, 1.04);
  EXPECT_EQ(s.friction_angle, 28.0);
  EXPECT_EQ(s.shear_modulus, 0.025);
  EXPECT_EQ(s.unloading_stiffness, 10000.0);
  EXPECT_EQ(s.unloading_growth, 0.0);  // left out
  EXPECT_EQ(s.viscosity, 2.5);
  EXPECT_EQ(s.where.line, 4);
}

TEST(SoilRefusal, EachFigureOutOfItsRange) {
  struct Case {
    const char* from;
    const char* to;
    std::vector<std::string> words;
  };
  // Beyond each end of each range; the words name the figure, its value
  // and the range (docs/soil.md's table).
  const Case cases[] = {
      {"<n>1.1</n>", "<n>0</n>", {"n 0 is out of range (0, 3]"}},
      {"<n>1.1</n>", "<n>-0.5</n>", {"n -0.5 is out of range (0, 3]"}},
      {"<n>1.1</n>", "<n>1e6</n>", {"n 1000000 is out of range (0, 3]"}},
      {"<kc>0.99</kc>", "<kc>-1</kc>", {"kc -1 kN/m^(n+1) is out of range [0, 10000]"}},
      {"<kc>0.99</kc>", "<kc>2e4</kc>", {"kc 20000 kN/m^(n+1)"}},
      {"<kphi>1528.43</kphi>", "<kphi>-3</kphi>", {"kphi -3 kN/m^(n+2)", "[0, 100000]"}},
      {"<kphi>1528.43</kphi>", "<kphi>1e300</kphi>", {"kphi 1e+300 kN/m^(n+2)"}},
      {"<cohesion>1.04</cohesion>", "<cohesion>-0.1</cohesion>", {"cohesion -0.1 kPa"}},
      {"<cohesion>1.04</cohesion>", "<cohesion>5000</cohesion>",
       {"cohesion 5000 kPa is out of range [0, 1000] kPa"}},
      {"<frictionAngle>28</frictionAngle>", "<frictionAngle>90</frictionAngle>",
       {"frictionAngle 90 deg is out of range [0, 60] deg"}},
      {"<frictionAngle>28</frictionAngle>", "<frictionAngle>-2</frictionAngle>",
       {"frictionAngle -2 deg"}},
      {"<shearModulus>0.025</shearModulus>", "<shearModulus>0</shearModulus>",
       {"shearModulus 0 m is out of range [0.0005, 1] m"}},
      {"<shearModulus>0.025</shearModulus>", "<shearModulus>1e-300</shearModulus>",
       {"shearModulus 1e-300 m"}},
      {"<shearModulus>0.025</shearModulus>", "<shearModulus>2</shearModulus>",
       {"shearModulus 2 m"}},
      {"<unloadingStiffness>10000</unloadingStiffness>",
       "<unloadingStiffness>-1</unloadingStiffness>",
       {"unloadingStiffness -1 kPa/m is out of range [0, 1000000] kPa/m"}},
      {"<unloadingStiffness>10000</unloadingStiffness>",
       "<unloadingStiffness>10000</unloadingStiffness><unloadingGrowth>-5</unloadingGrowth>",
       {"unloadingGrowth -5 kPa/m^2 is out of range [0, 100000000] kPa/m^2"}},
      {"<unloadingStiffness>10000</unloadingStiffness>",
       "<unloadingStiffness>1e9</unloadingStiffness>", {"unloadingStiffness 1000000000 kPa/m"}},
      {"<viscosity>0</viscosity>", "<viscosity>-1</viscosity>", {"viscosity -1 kPa s/m"}},
      {"<viscosity>0</viscosity>", "<viscosity>1e5</viscosity>",
       {"viscosity 100000 kPa s/m is out of range [0, 10000] kPa s/m"}},
      {"<n>1.1</n>", "<n>nan</n>", {"soil n", "'nan' is not a finite number"}},
      {"<kphi>1528.43</kphi>", "<kphi>inf</kphi>", {"soil kphi", "'inf' is not a finite number"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    std::vector<std::string> words = c.words;
    words.push_back("material 'ground' soil");
    ExpectInlineRefused(Swap(kInlineSoil, c.from, c.to), c.to, words);
  }
}

TEST(SoilRefusal, KcAndKphiBothZero) {
  ExpectInlineRefused(
      Swap(Swap(kInlineSoil, "<kc>0.99</kc>", "<kc>0</kc>"), "<kphi>1528.43<", "<kphi>0<"),
      "<kc>", {"kc and kphi are both 0"});
}

TEST(SoilRefusal, AWrittenOutSoilLackingFigures) {
  const std::string soil = Swap(Swap(kInlineSoil, "<kphi>1528.43</kphi>\n", ""),
                                "<viscosity>0</viscosity>\n", "");
  ExpectInlineRefused(soil, "<soil>", {"material 'ground' soil", "lacks kphi, viscosity"});
}

TEST(SoilRefusal, ANameWithoutALibraryAndALibraryWithoutAName) {
  ExpectInlineRefused(Swap(kInlineSoil, "<soil>", "<soil name=\"dry_sand\">"), "<soil",
                      {"name 'dry_sand' without library="});
  const std::string xml = WorldWithSoil("<soil library=\"../soils/wong2008.xml\"/>");
  ExpectRefused(ParseWorld(xml, kWorldFile), xml, kWorldFile, "<soil",
                {"library '../soils/wong2008.xml' without name="});
}

TEST(SoilRefusal, AnUnknownEntryWithTheNearestName) {
  const std::string xml =
      WorldWithSoil("<soil library=\"../soils/wong2008.xml\" name=\"dry_snad\"/>");
  ExpectRefused(ParseWorld(xml, kWorldFile), xml, kWorldFile, "<soil",
                {"has no soil 'dry_snad'", "did you mean 'dry_sand'?", "lunar_nominal"});
}

TEST(SoilRefusal, AnOverrideOutOfRangeAtItsLineInTheWorld) {
  const std::string xml = WorldWithSoil(
      "<soil library=\"../soils/wong2008.xml\" name=\"dry_sand\">\n<frictionAngle>95"
      "</frictionAngle></soil>");
  ExpectRefused(ParseWorld(xml, kWorldFile), xml, kWorldFile, "<frictionAngle>",
                {"frictionAngle 95 deg"});
}

TEST(SoilRefusal, AnUnreadableLibrary) {
  const std::string xml = WorldWithSoil("<soil library=\"no_such_soils.xml\" name=\"x\"/>");
  const WorldLoadResult result = ParseWorld(xml, "dir/soil.xml", Serve({}));
  EXPECT_FALSE(result.world);
  ASSERT_GE(result.diagnostics.size(), 2u) << result.diagnostics.Format();
  const Diagnostic& file = result.diagnostics.items()[0];
  EXPECT_EQ(file.file, "dir/no_such_soils.xml");
  EXPECT_EQ(file.message, "cannot read soil library file");
  const Diagnostic& at = result.diagnostics.items().back();
  EXPECT_EQ(at.file, "dir/soil.xml");
  EXPECT_EQ(at.line, LineOf(xml, "<soil"));
  EXPECT_NE(at.message.find("cannot use soil library 'no_such_soils.xml'"), std::string::npos)
      << at.message;
}

// A library entry out of range is refused in the library, at its line,
// once however many materials name it; each of them says it cannot use it.
TEST(SoilRefusal, AnInvalidLibraryIsReportedOnceAtItsLine) {
  const std::string library =
      "<soils>\n<soil name=\"mud\" source=\"made up\"><n>1</n><kc>1</kc><kphi>100</kphi>"
      "<cohesion>1</cohesion><frictionAngle>20</frictionAngle>\n<shearModulus>-0.01"
      "</shearModulus><unloadingStiffness>1e4</unloadingStiffness><viscosity>0</viscosity>"
      "</soil>\n</soils>";
  const std::string xml =
      "<world>\n<material name=\"a\"><soil library=\"mud.xml\" name=\"mud\"/></material>\n"
      "<material name=\"b\"><soil library=\"./mud.xml\" name=\"mud\"/></material>\n</world>";
  const WorldLoadResult result = ParseWorld(xml, "w/soil.xml", Serve({{"w/mud.xml", library}}));
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 3u) << result.diagnostics.Format();
  const Diagnostic& in_library = result.diagnostics.items()[0];
  EXPECT_EQ(in_library.file, "w/mud.xml");
  EXPECT_EQ(in_library.line, LineOf(library, "<shearModulus>"));
  EXPECT_NE(in_library.message.find("soil 'mud': shearModulus -0.01 m"), std::string::npos)
      << in_library.message;
  for (int k = 1; k <= 2; ++k) {
    const Diagnostic& d = result.diagnostics.items()[static_cast<size_t>(k)];
    EXPECT_EQ(d.file, "w/soil.xml");
    EXPECT_EQ(d.line, k + 1);
    EXPECT_NE(d.message.find("(1 problem)"), std::string::npos) << d.message;
  }
}

TEST(SoilRefusal, ALibraryThatBreaksItsDtd) {
  const std::string library = "<soils>\n<soil name=\"mud\"><n>1</n></soil>\n</soils>";
  const std::string xml = WorldWithSoil("<soil library=\"mud.xml\" name=\"mud\"/>");
  const WorldLoadResult result = ParseWorld(xml, "soil.xml", Serve({{"mud.xml", library}}));
  EXPECT_FALSE(result.world);
  ASSERT_GE(result.diagnostics.size(), 2u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].file, "mud.xml");
  EXPECT_EQ(result.diagnostics.items()[0].line, 2);
  EXPECT_EQ(result.diagnostics.items().back().file, "soil.xml");
  EXPECT_EQ(result.diagnostics.items().back().line, LineOf(xml, "<soil"));
}

TEST(SoilRefusal, ASoilOnAnObject) {
  const std::string xml =
      "<world>\n<material name=\"sand\">" + kInlineSoil + "</material>\n"
      "<object type=\"Box\" name=\"Crate\" material=\"sand\" static=\"true\">"
      "<size><x>1</x><y>1</y><z>1</z></size>" + Pose(0, 1, 0) + "</object>\n</world>";
  ExpectRefused(ParseWorld(xml, "soil.xml"), xml, "soil.xml", "<object",
                {"object 'Crate'", "material 'sand' (soil.xml:2) is a soil",
                 "only for a ground (the surface or the heightfield)"});
}

TEST(SoilRefusal, ASoilOnARobotsBody) {
  const std::string robot =
      "<robot name=\"Cart\">\n<body type=\"Sphere\" name=\"Wheel\" material=\"sand\">"
      "<mass>1</mass><radius>0.2</radius>" + Pose(0, 0.2, 0) + "</body>\n</robot>";
  const std::string xml = "<world>\n<material name=\"sand\">" + kInlineSoil +
                          "</material>\n<robot name=\"C1\" file=\"cart.xml\"/>\n</world>";
  const WorldLoadResult result = ParseWorld(xml, "soil.xml", Serve({{"cart.xml", robot}}));
  ExpectRefused(result, robot, "cart.xml", "<body",
                {"body 'Wheel' of robot 'C1'", "material 'sand' (soil.xml:2) is a soil"});
}

TEST(SoilMessage, SimModelCarriesTheSoil) {
  const WorldLoadResult result = ParseWorld(
      "<world><material name=\"ground\">" + kInlineSoil +
          "</material><material name=\"ice\"><mu>0.02</mu></material></world>",
      "soil.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const material_t soil = MaterialMessage(*result.world->FindMaterial("ground"));
  EXPECT_TRUE(soil.is_soil);
  EXPECT_EQ(soil.soil_name, "ground");
  EXPECT_EQ(soil.soil_n, 1.1);
  EXPECT_EQ(soil.soil_kc, 0.99);
  EXPECT_EQ(soil.soil_kphi, 1528.43);
  EXPECT_EQ(soil.soil_cohesion, 1.04);
  EXPECT_EQ(soil.soil_friction_angle, 28.0);
  EXPECT_EQ(soil.soil_shear_modulus, 0.025);
  EXPECT_EQ(soil.soil_unloading_stiffness, 10000.0);
  EXPECT_EQ(soil.soil_viscosity, 0.0);
  const material_t ice = MaterialMessage(*result.world->FindMaterial("ice"));
  EXPECT_FALSE(ice.is_soil);
  EXPECT_EQ(ice.soil_name, "");
  EXPECT_EQ(ice.soil_kphi, 0.0);
}

}  // namespace
}  // namespace simpartner::model
