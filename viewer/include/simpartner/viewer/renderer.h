// Draws a Scene with fixed-function OpenGL (GL 1.x/2.1 compatibility
// calls only, which Mesa's llvmpipe and every desktop driver have): the
// plane or heightfield with its grid, the ruts in soft soil, the bodies solid with lighting or as
// wireframe, body frames, force arrows, scanner rays and the HUD text.
// Needs a current GL context for its whole life.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/viewer/camera.h"
#include "simpartner/viewer/ground_look.h"
#include "simpartner/viewer/mesh.h"
#include "simpartner/viewer/toggles.h"
#include "simpartner/png_image.h"
#include "simpartner/viewer/scene.h"

namespace simpartner::viewer {

using Color3 = std::array<float, 3>;  // RGB 0..1

struct HudLine {
  std::string text;
  Color3 color{1, 1, 1};
};

// A camera's image shown in the bottom-right corner, with a label above.
struct Inset {
  int width = 0;
  int height = 0;
  const uint8_t* rgb = nullptr;  // width * height * 3 bytes, rows top to bottom
  std::string label;
};

// The overlays of one frame.
struct Hud {
  std::vector<HudLine> top;     // status line, warnings
  std::vector<HudLine> bottom;  // hints
  std::vector<std::string> key_help;  // shown in a box when not empty
  std::optional<Inset> inset;
};

// Colour (RGB 0..1) a body is drawn in: robots in WorkPartner yellow with
// dark wheels, moving objects red, fixed objects wood brown. Parts of a
// robot alternate slightly in brightness so that neighbours stay apart.
Color3 BodyColor(const model_t& model, int body);
// Background colour (RGB 0..1).
Color3 SkyColor();

// Scale of the force arrows [m per N].
inline constexpr double kForceArrowScale = 1.0 / 1000.0;

// The current read buffer (the window's or a framebuffer object's), rows
// top to bottom: colour, and depth as the depth buffer holds it (0 at the
// near plane, 1 at the far plane and where nothing was drawn).
RgbImage ReadRgb(int width, int height);
std::vector<float> ReadDepth(int width, int height);

class Renderer {
 public:
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void Draw(const Scene& scene, const Camera& camera, const Toggles& toggles, const Hud& hud,
            int width, int height);
  void Draw(const Scene& scene, const Viewpoint& viewpoint, const Toggles& toggles,
            const Hud& hud, int width, int height);
  // The frame just drawn in the window (call before swapping buffers).
  RgbImage ReadPixels(int width, int height) const;
  int bodies_drawn() const { return bodies_drawn_; }

 private:
  void RebuildModel(const Scene& scene);
  void ReleaseModel();
  void DrawGround(const Scene& scene, const Viewpoint& viewpoint, const Toggles& toggles);
  void DrawRuts(const Scene& scene);
  // Rebuilds the ruts' meshes that are due (kRutRebuildInterval); true
  // when there are ruts to draw.
  bool RebuildRuts(const Scene& scene);
  void DrawBodies(const Scene& scene, const Toggles& toggles);
  void DrawOverlays(const Scene& scene, const Viewpoint& viewpoint, const Toggles& toggles);
  void DrawHud(const Hud& hud, int width, int height);
  void DrawInset(const Inset& inset, int width, int height);
  void DrawText(const std::string& text, float x, float y, float scale, const Color3& color,
                float alpha = 1.0f);

  struct BufferMesh;

  int64_t model_generation_ = -1;
  std::vector<unsigned> body_lists_;  // one display list per body (0: nothing to draw)
  std::unique_ptr<BufferMesh> heightfield_;
  Lines heightfield_grid_;
  // The grounds' looks, from their materials (ground_look.h).
  Color3 plane_color_{0.50f, 0.55f, 0.50f};
  GroundKind field_kind_ = GroundKind::kRigid;
  // The meshes of the scene's ruts of one ground (RutMesh, RutOpeningMesh),
  // of generation `generation`.
  struct RutLayer {
    std::unique_ptr<BufferMesh> floor, opening;
    int64_t generation = -1;
    std::chrono::steady_clock::time_point built{};
  };
  std::array<RutLayer, 2> ruts_;  // by ground (soil_ruts_t::GROUND_*)
  // The ruts' mesh is rebuilt at most this often (its changes come ten
  // times a second; rebuilding 55,000 cells each time cost 40 % of the
  // frame rate).
  static constexpr std::chrono::milliseconds kRutRebuildInterval{500};
  unsigned font_texture_ = 0;
  unsigned inset_texture_ = 0;
  int font_width_ = 0;
  int font_height_ = 0;
  int bodies_drawn_ = 0;
  // Light directions of the current frame (world frame, unit).
  Eigen::Vector3d sun_ = Eigen::Vector3d::UnitY();
  Eigen::Vector3d fill_ = Eigen::Vector3d::UnitY();
};

}  // namespace simpartner::viewer
