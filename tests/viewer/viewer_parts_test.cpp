// The viewer's smaller parts without a display: the built-in font, PNG files,
// the command line and the key bindings.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "simpartner/bitmap_font.h"
#include "simpartner/bus_url.h"
#include "simpartner/viewer/keys.h"
#include "simpartner/viewer/options.h"
#include "simpartner/png_image.h"

namespace simpartner::viewer {
namespace {

std::filesystem::path TempPath(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("sp_viewer_parts_" + std::to_string(::getpid()) + "_" + name);
}

int Pixels(const std::array<uint8_t, kGlyphHeight>& rows) {
  int n = 0;
  for (uint8_t r : rows) n += __builtin_popcount(r);
  return n;
}

TEST(FontTest, EveryPrintableCharacterHasItsOwnGlyph) {
  std::set<std::array<uint8_t, kGlyphHeight>> seen;
  for (char c = kFirstGlyph + 1; c <= kLastGlyph; ++c) {
    const auto g = Glyph(c);
    EXPECT_GT(Pixels(g), 2) << "'" << c << "'";
    for (uint8_t row : g) EXPECT_LT(row, 32) << "'" << c << "' is wider than 5 pixels";
    EXPECT_TRUE(seen.insert(g).second) << "'" << c << "' looks like another character";
  }
  EXPECT_EQ(Pixels(Glyph(' ')), 0);
  // Shapes a reader relies on: 'I' is a vertical bar with serifs, '-' one row.
  EXPECT_EQ(Glyph('-')[3], 0x1F);
  EXPECT_EQ(Pixels(Glyph('-')), 5);
  EXPECT_EQ(Glyph('I')[0], 0x0E);
  EXPECT_EQ(Glyph('I')[3], 0x04);
  // Outside the table: '?'.
  EXPECT_EQ(Glyph('\t'), Glyph('?'));
}

TEST(FontTest, AtlasHoldsEveryGlyphInItsCell) {
  const FontAtlas atlas = MakeFontAtlas();
  EXPECT_EQ(atlas.height, kCellHeight);
  EXPECT_EQ(atlas.width, kCellWidth * (kLastGlyph - kFirstGlyph + 1));
  const int cell = 'A' - kFirstGlyph;
  int set = 0;
  for (int y = 0; y < kCellHeight; ++y)
    for (int x = 0; x < kCellWidth; ++x)
      set += atlas.coverage[static_cast<size_t>(y) * atlas.width + cell * kCellWidth + x] == 255;
  EXPECT_EQ(set, Pixels(Glyph('A')));
  // The spacing column and row stay empty.
  for (int y = 0; y < kCellHeight; ++y)
    EXPECT_EQ(atlas.coverage[static_cast<size_t>(y) * atlas.width + cell * kCellWidth + 5], 0);
}

TEST(PngTest, WrittenImageReadsBackTheSame) {
  RgbImage image;
  image.width = 7;
  image.height = 3;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 7; ++x)
      image.pixels.insert(image.pixels.end(), {static_cast<uint8_t>(x * 30),
                                               static_cast<uint8_t>(y * 100), 200});
  const std::string path = TempPath("round.png").string();
  WritePng(path, image);
  const RgbImage back = ReadPng(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_EQ(back.At(6, 2).r, 180);
  EXPECT_EQ(back.At(6, 2).g, 200);
}

TEST(PngTest, ErrorsNameTheFile) {
  RgbImage image;
  image.width = 2;
  image.height = 2;
  image.pixels.assign(12, 0);
  try {
    WritePng("/nonexistent-dir/x.png", image);
    FAIL() << "no error";
  } catch (const PngError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.png: cannot write"), std::string::npos)
        << e.what();
  }
  const std::string not_png = TempPath("not.png").string();
  std::ofstream(not_png) << "this is text";
  try {
    ReadPng(not_png);
    FAIL() << "no error";
  } catch (const PngError& e) {
    EXPECT_NE(std::string(e.what()).find(not_png + ": "), std::string::npos) << e.what();
  }
  std::filesystem::remove(not_png);
  image.pixels.resize(5);
  EXPECT_THROW(WritePng(TempPath("short.png").string(), image), PngError);
}

// A depth image of SIM_IMAGE as 16-bit grey millimetres (simpartner-cmd
// read --depth --out). ReadPng keeps the high byte of each sample: mm / 256.
TEST(PngTest, DepthImagesAreWrittenInMillimetres) {
  image_t depth;
  depth.width = 5;
  depth.height = 1;
  depth.format = image_t::FORMAT_DEPTH_F32;
  const float metres[] = {1.0f, 10.0f, std::numeric_limits<float>::infinity(), 70.0f, 0.5f};
  depth.data.resize(sizeof metres);
  std::memcpy(depth.data.data(), metres, sizeof metres);
  depth.num_bytes = static_cast<int32_t>(depth.data.size());
  const std::string path = TempPath("depth.png").string();
  WriteImagePng(path, depth);
  const RgbImage back = ReadPng(path);
  std::filesystem::remove(path);
  ASSERT_EQ(back.width, 5);
  // 1000, 10000 mm; nothing (inf) and beyond 65.535 m are 0; 500 mm.
  const int high_bytes[] = {1000 / 256, 10000 / 256, 0, 0, 500 / 256};
  for (int x = 0; x < 5; ++x) EXPECT_EQ(back.At(x, 0).r, high_bytes[x]) << "pixel " << x;
  depth.data.resize(12);  // not 5 floats
  try {
    WriteImagePng(path, depth);
    FAIL() << "no error";
  } catch (const PngError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": depth image is 5 x 1 with 12 bytes"),
              std::string::npos)
        << e.what();
  }
}

ViewerOptions Options(std::vector<std::string> args) {
  args.insert(args.begin(), {"--params", "/dev/null"});
  const CommandLine cl = ParseCommandLine(ViewerCommandLine(), args);
  return MakeViewerOptions(cl, LoadParameters(cl.parameter_sources()));
}

// The command line's refusal or the options' ConfigError.
std::string ErrorOf(std::vector<std::string> args) {
  try {
    Options(std::move(args));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(OptionsTest, DefaultsAndScreenshotFlags) {
  const ViewerOptions d = Options({});
  EXPECT_EQ(d.width, 1280);
  EXPECT_EQ(d.height, 720);
  // Its socket asks for the large receive buffer: with the kernel's
  // default LCM warned "the kernel UDP receive buffer is very small" and
  // a viewer beside a fast sim missed states.
  EXPECT_EQ(d.lcm_url, WithReceiveBuffer(kDefaultLcmUrl));
  EXPECT_NE(d.lcm_url.find("recv_buf_size="), std::string::npos);
  EXPECT_TRUE(d.screenshot.empty());
  EXPECT_TRUE(d.toggles.follow);
  EXPECT_FALSE(d.toggles.wireframe);

  const ViewerOptions s = Options({"--screenshot", "a.png", "--after=1.5", "--width", "800",
                                   "--lcm-url", "udpm://239.255.76.67:7700?ttl=0"});
  EXPECT_EQ(s.screenshot, "a.png");
  EXPECT_DOUBLE_EQ(s.after_seconds, 1.5);
  EXPECT_EQ(s.width, 800);
  EXPECT_EQ(s.lcm_url, "udpm://239.255.76.67:7700?ttl=0&recv_buf_size=4194304");
  // A screenshot without a time is taken after 2 s.
  EXPECT_DOUBLE_EQ(Options({"--screenshot", "b.png"}).after_seconds, 2.0);
  EXPECT_EQ(Options({"--screenshot", "b.png", "--frames", "5"}).after_frames, 5);
  EXPECT_EQ(d.nice, 5);
  EXPECT_EQ(Options({"--nice", "0"}).nice, 0);
}

TEST(OptionsTest, CameraShowAndHide) {
  const ViewerOptions o =
      Options({"--camera", "1,2,3,45,-10,7.5", "--show", "wireframe,contacts", "--hide=grid"});
  ASSERT_TRUE(o.camera.has_value());
  EXPECT_DOUBLE_EQ(o.camera->target[2], 3);
  EXPECT_DOUBLE_EQ(o.camera->pitch_deg, -10);
  EXPECT_DOUBLE_EQ(o.camera->distance, 7.5);
  EXPECT_FALSE(o.toggles.follow);  // a fixed camera does not follow
  EXPECT_TRUE(o.toggles.wireframe);
  EXPECT_TRUE(o.toggles.contact_forces);
  EXPECT_FALSE(o.toggles.grid);
}

TEST(OptionsTest, BadValuesNameTheFlagAndValue) {
  EXPECT_NE(ErrorOf({"--width", "wide"}).find("--width: value 'wide' is not a number from 64"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"--fps", "-1"}).find("--fps: value '-1'"), std::string::npos);
  EXPECT_NE(ErrorOf({"--nice", "20"}).find("--nice: value '20' is not a number from 0 to 19"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"--camera", "1,2,3"}).find("--camera: value '1,2,3' is not 6 numbers"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"--camera", "0,0,0,0,95,5"}).find("--camera: value '95' is not a number from -89 to 89"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"--show", "wirefram"}).find("--show: 'wirefram' is not one of wireframe"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"--after", "3"}).find("--after: only applies with --screenshot FILE"),
            std::string::npos);
  EXPECT_NE(ErrorOf({"extra"}).find("unexpected argument 'extra'"), std::string::npos);
}

TEST(KeysTest, EveryBindingIsListedAndKeysDoNotClash) {
  EXPECT_EQ(ActionForKey(SDLK_SPACE), KeyAction::kTogglePause);
  EXPECT_EQ(ActionForKey(SDLK_w), KeyAction::kToggleWireframe);
  EXPECT_EQ(ActionForKey(SDLK_F1), KeyAction::kToggleHelp);
  EXPECT_EQ(ActionForKey(SDLK_h), KeyAction::kToggleHelp);
  EXPECT_EQ(ActionForKey(SDLK_r), KeyAction::kReset);
  EXPECT_EQ(ActionForKey(SDLK_n), KeyAction::kStep);
  EXPECT_EQ(ActionForKey(SDLK_z), KeyAction::kNone);
  EXPECT_TRUE(IsFlyAction(ActionForKey(SDLK_UP)));
  EXPECT_FALSE(IsFlyAction(ActionForKey(SDLK_SPACE)));
  // The on-screen list names each bound key.
  std::string help;
  for (const std::string& line : KeyHelpLines()) help += line + "\n";
  for (const char* key : {"space", "n / m", "\nr ", "\nw ", "\nb ", "\nc ", "\nj ", "\ns ", "\ng ",
                          "\nu ", "\nf ", "\np ", "F1", "Home", "Esc", "PageUp", "arrow keys"})
    EXPECT_NE(help.find(key), std::string::npos) << key;
}

TEST(OptionsTest, HelpListsFlagsAndKeys) {
  const std::string usage = FormatHelp(ViewerCommandLine());
  for (const char* text : {"--screenshot", "--after", "--camera", "--show", "--fps",
                           "SIM_MODEL_REQUEST", "pause / resume"})
    EXPECT_NE(usage.find(text), std::string::npos) << text;
}

}  // namespace
}  // namespace simpartner::viewer
