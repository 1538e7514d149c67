#include "simpartner/viewer/renderer.h"

// Buffer objects (GL 1.5) are called directly (GL_GLEXT_PROTOTYPES, this
// library's definition): libGL (glvnd) exports them.
#include <SDL2/SDL_opengl.h>

#include <algorithm>
#include <cmath>

#include "simpartner/bitmap_font.h"
#include "simpartner/viewer/ground_look.h"
#include "simpartner/viewer/mesh.h"

namespace simpartner::viewer {
namespace {

using Color = Color3;

constexpr Color kGridColor{0.30f, 0.34f, 0.32f};
constexpr Color kFieldGridColor{0.45f, 0.52f, 0.62f};
constexpr Color kContactForceColor{0.95f, 0.15f, 0.15f};
constexpr Color kJointForceColor{0.15f, 0.75f, 0.95f};
constexpr Color kRayColor{1.0f, 0.1f, 0.1f};
constexpr Color kHitColor{1.0f, 0.9f, 0.1f};

constexpr GLfloat kSunDiffuse[4] = {0.68f, 0.68f, 0.65f, 1};
constexpr GLfloat kFillDiffuse[4] = {0.22f, 0.23f, 0.27f, 1};
constexpr GLfloat kAmbient[4] = {0.28f, 0.28f, 0.30f, 1};
constexpr double kPlaneGridHalf = 30.0;  // [m] grid lines this far around the point looked at

constexpr float kHudScale = 2.0f;  // font pixels per screen pixel
constexpr float kHudLineHeight = kCellHeight * kHudScale + 4;

void SetColor(const Color& c, float alpha = 1.0f) { glColor4f(c[0], c[1], c[2], alpha); }

void Vertex(const Eigen::Vector3d& p) { glVertex3d(p.x(), p.y(), p.z()); }

// Binds `texture` (left bound) and loads it with bytes of `format`
// (GL_ALPHA, GL_RGB), clamped at its edges.
void LoadTexture(GLuint texture, GLint filter, GLenum format, int width, int height,
                 const void* pixels) {
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(format), width, height, 0, format,
               GL_UNSIGNED_BYTE, pixels);
}

// Compiles a mesh (with its colours if it has them) into a display list.
unsigned CompileMesh(const Mesh& mesh) {
  if (mesh.positions.empty()) return 0;
  const unsigned list = glGenLists(1);
  glNewList(list, GL_COMPILE);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, sizeof(Eigen::Vector3f), mesh.positions.data());
  glNormalPointer(GL_FLOAT, sizeof(Eigen::Vector3f), mesh.normals.data());
  if (!mesh.colors.empty()) {
    glEnableClientState(GL_COLOR_ARRAY);
    glColorPointer(3, GL_FLOAT, sizeof(Eigen::Vector3f), mesh.colors.data());
  }
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(mesh.positions.size()));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glEndList();
  return list;
}

}  // namespace

// A large indexed mesh in buffer objects: positions, normals and colours
// one after the other in one buffer, the indices in another.
struct Renderer::BufferMesh {
  GLuint vertices = 0;
  GLuint indices = 0;
  GLsizei index_count = 0;
  size_t normals_offset = 0;
  size_t colors_offset = 0;

  explicit BufferMesh(const Mesh& mesh) {
    const size_t block = mesh.positions.size() * sizeof(Eigen::Vector3f);
    normals_offset = block;
    colors_offset = 2 * block;
    glGenBuffers(1, &vertices);
    glBindBuffer(GL_ARRAY_BUFFER, vertices);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(3 * block), nullptr, GL_STATIC_DRAW);
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(block), mesh.positions.data());
    glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(block), static_cast<GLsizeiptr>(block),
                    mesh.normals.data());
    glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(2 * block),
                    static_cast<GLsizeiptr>(block), mesh.colors.data());
    glGenBuffers(1, &indices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    index_count = static_cast<GLsizei>(mesh.indices.size());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  }
  ~BufferMesh() {
    glDeleteBuffers(1, &vertices);
    glDeleteBuffers(1, &indices);
  }
  BufferMesh(const BufferMesh&) = delete;
  BufferMesh& operator=(const BufferMesh&) = delete;

  void Draw() const {
    glBindBuffer(GL_ARRAY_BUFFER, vertices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_NORMAL_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, nullptr);
    glNormalPointer(GL_FLOAT, 0, reinterpret_cast<const void*>(normals_offset));
    glColorPointer(3, GL_FLOAT, 0, reinterpret_cast<const void*>(colors_offset));
    glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_NORMAL_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  }
};

namespace {

void DrawLines(const Lines& lines) {
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, sizeof(Eigen::Vector3f), lines.positions.data());
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(lines.positions.size()));
  glDisableClientState(GL_VERTEX_ARRAY);
}

void DrawMesh(const Mesh& mesh) {
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, sizeof(Eigen::Vector3f), mesh.positions.data());
  glNormalPointer(GL_FLOAT, sizeof(Eigen::Vector3f), mesh.normals.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(mesh.positions.size()));
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

// An arrow from `from` along `vector`, its head facing the camera.
void DrawArrow(const Eigen::Vector3d& from, const Eigen::Vector3d& vector,
               const Eigen::Vector3d& eye) {
  const double length = vector.norm();
  if (length < 1e-4) return;
  const Eigen::Vector3d tip = from + vector;
  const Eigen::Vector3d dir = vector / length;
  Eigen::Vector3d side = dir.cross(eye - tip);
  if (side.norm() < 1e-9) side = dir.unitOrthogonal();
  side.normalize();
  const double head = std::min(0.25 * length, 0.08);
  glBegin(GL_LINES);
  Vertex(from);
  Vertex(tip);
  glEnd();
  glBegin(GL_TRIANGLES);
  Vertex(tip);
  Vertex(tip - head * dir + 0.4 * head * side);
  Vertex(tip - head * dir - 0.4 * head * side);
  glEnd();
}

Eigen::Vector3d V(const double v[3]) { return Eigen::Vector3d(v[0], v[1], v[2]); }

}  // namespace

Color3 SkyColor() { return {0.47f, 0.64f, 0.86f}; }

Color3 BodyColor(const model_t& model, int body) {
  const body_t& b = model.bodies[static_cast<size_t>(body)];
  Color c;
  if (b.robot >= 0) {
    c = b.geometry.kind == geometry_t::KIND_CYLINDER ? Color{0.20f, 0.20f, 0.22f}
                                                     : Color{0.95f, 0.68f, 0.12f};
    const float shade = (body % 2 == 0) ? 1.0f : 0.86f;
    for (float& v : c) v *= shade;
  } else if (b.is_static) {
    c = {0.58f, 0.42f, 0.26f};
  } else {
    c = {0.80f, 0.25f, 0.20f};
  }
  return c;
}

Renderer::Renderer() {
  const FontAtlas atlas = MakeFontAtlas();
  font_width_ = atlas.width;
  font_height_ = atlas.height;
  glGenTextures(1, &font_texture_);
  LoadTexture(font_texture_, GL_NEAREST, GL_ALPHA, atlas.width, atlas.height,
              atlas.coverage.data());

  glBindTexture(GL_TEXTURE_2D, 0);
}

Renderer::~Renderer() {
  ReleaseModel();
  if (font_texture_ != 0) glDeleteTextures(1, &font_texture_);
  if (inset_texture_ != 0) glDeleteTextures(1, &inset_texture_);
}

void Renderer::ReleaseModel() {
  for (unsigned list : body_lists_)
    if (list != 0) glDeleteLists(list, 1);
  body_lists_.clear();
  heightfield_.reset();
  heightfield_grid_.positions.clear();
  for (RutLayer& layer : ruts_) {
    layer.floor.reset();
    layer.opening.reset();
    layer.generation = -1;
  }
}

void Renderer::RebuildModel(const Scene& scene) {
  ReleaseModel();
  model_generation_ = scene.model_generation();
  if (!scene.has_model()) return;
  const model_t& m = scene.model();
  for (const body_t& b : m.bodies) body_lists_.push_back(CompileMesh(GeometryMesh(b.geometry)));
  // Each ground in its material's colour: rigid, or the soil it is.
  plane_color_ = GroundColor(GroundKindOf(m, m.plane_material));
  field_kind_ = GroundKindOf(m, m.heightfield.material);
  if (m.heightfield.present) {
    const Color low = FieldLowColor(field_kind_), high = FieldHighColor(field_kind_);
    heightfield_ = std::make_unique<BufferMesh>(
        HeightfieldMesh(m.heightfield, scene.Up(), Eigen::Vector3f(low[0], low[1], low[2]),
                        Eigen::Vector3f(high[0], high[1], high[2])));
    // Lines cost llvmpipe per segment: straight stretches become one
    // segment, lifted above the surface by more than they may cut into it.
    heightfield_grid_ = HeightfieldGrid(m.heightfield, scene.Up(), 1.0, 0.012, 0.006);
  }
}

void Renderer::Draw(const Scene& scene, const Camera& camera, const Toggles& toggles,
                    const Hud& hud, int width, int height) {
  Draw(scene, camera.ToViewpoint(static_cast<double>(width) / height), toggles, hud, width,
       height);
}

void Renderer::Draw(const Scene& scene, const Viewpoint& viewpoint, const Toggles& toggles,
                    const Hud& hud, int width, int height) {
  if (scene.model_generation() != model_generation_) RebuildModel(scene);
  glViewport(0, 0, width, height);
  const Color sky = SkyColor();
  glClearColor(sky[0], sky[1], sky[2], 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);

  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(viewpoint.projection.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(viewpoint.view.data());

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
  glEnable(GL_NORMALIZE);  // body meshes are not scaled, but keep normals unit anyway
  glShadeModel(GL_SMOOTH);
  // Lights move with the camera (a sun above and to the right of the eye,
  // a dimmer fill from the left), so the faces turned to the viewer always
  // differ in shade, from any side.
  const Eigen::Vector3d up = scene.Up();
  const Eigen::Vector3d toward_eye = (viewpoint.eye - viewpoint.looked_at).normalized();
  // A camera looking straight along up takes its right from any horizontal.
  Eigen::Vector3d right = up.cross(toward_eye);
  right = right.norm() > 1e-6 ? right.normalized() : up.unitOrthogonal();
  sun_ = (0.75 * up + 0.55 * right + 0.35 * toward_eye).normalized();
  fill_ = (0.2 * up - 0.7 * right + 0.4 * toward_eye).normalized();
  const Eigen::Vector3d& sun = sun_;
  const Eigen::Vector3d& fill = fill_;
  const GLfloat sun_position[4] = {static_cast<float>(sun.x()), static_cast<float>(sun.y()),
                                   static_cast<float>(sun.z()), 0};
  const GLfloat fill_position[4] = {static_cast<float>(fill.x()), static_cast<float>(fill.y()),
                                    static_cast<float>(fill.z()), 0};
  const GLfloat* sun_diffuse = kSunDiffuse;
  const GLfloat* fill_diffuse = kFillDiffuse;
  const GLfloat* ambient = kAmbient;
  const GLfloat black[4] = {0, 0, 0, 1};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);  // terrain seen from below, open shapes
  glLightfv(GL_LIGHT0, GL_POSITION, sun_position);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, sun_diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, black);
  glLightfv(GL_LIGHT0, GL_AMBIENT, black);
  glLightfv(GL_LIGHT1, GL_POSITION, fill_position);
  glLightfv(GL_LIGHT1, GL_DIFFUSE, fill_diffuse);
  glLightfv(GL_LIGHT1, GL_SPECULAR, black);
  glLightfv(GL_LIGHT1, GL_AMBIENT, black);
  glEnable(GL_LIGHT0);
  glEnable(GL_LIGHT1);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glEnable(GL_COLOR_MATERIAL);

  if (scene.has_model()) {
    DrawGround(scene, viewpoint, toggles);
    DrawRuts(scene);
    DrawBodies(scene, toggles);
    DrawOverlays(scene, viewpoint, toggles);
  } else {
    bodies_drawn_ = 0;
    if (toggles.grid) {
      // Something to look at while waiting: the y = 0 grid.
      glDisable(GL_LIGHTING);
      SetColor(kGridColor);
      const double plane[4] = {0, 1, 0, 0};
      DrawLines(PlaneGrid(plane, viewpoint.looked_at, 20, 1));
    }
  }
  DrawHud(hud, width, height);
}

void Renderer::DrawGround(const Scene& scene, const Viewpoint& viewpoint, const Toggles& toggles) {
  const model_t& m = scene.model();
  const Eigen::Vector3d up = scene.Up();
  // The heightfield first, then the plane, so that the part of the plane
  // hidden under the terrain fails the depth test early.
  if (heightfield_) {
    if (toggles.wireframe) {
      glDisable(GL_LIGHTING);
      glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    } else {
      glEnable(GL_LIGHTING);
    }
    heightfield_->Draw();
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  if (m.has_plane) {
    // A square around the point looked at, large enough to reach the
    // horizon of any sensible view.
    const double half = std::max(200.0, 20 * viewpoint.distance);
    glEnable(GL_LIGHTING);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);  // grid lines and bodies resting on it win the depth test
    SetColor(plane_color_);
    DrawMesh(PlaneMesh(m.plane, viewpoint.looked_at, half));
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  if (!toggles.grid) return;
  glDisable(GL_LIGHTING);
  glLineWidth(1);
  if (m.has_plane) {
    // The lines fade into the plane with distance (fog of the plane's own
    // lit colour) instead of crowding into a flickering band at the horizon.
    const Eigen::Vector3d n = Eigen::Vector3d(m.plane[0], m.plane[1], m.plane[2]).normalized();
    GLfloat lit[4] = {0, 0, 0, 1};
    for (int k = 0; k < 3; ++k)
      lit[k] = std::min(1.0f, plane_color_[static_cast<size_t>(k)] *
                                  (kAmbient[k] + kSunDiffuse[k] * std::max(0.0f, static_cast<float>(n.dot(sun_))) +
                                   kFillDiffuse[k] * std::max(0.0f, static_cast<float>(n.dot(fill_)))));
    glEnable(GL_FOG);
    glFogi(GL_FOG_MODE, GL_LINEAR);
    glFogf(GL_FOG_START, static_cast<float>(0.3 * kPlaneGridHalf));
    glFogf(GL_FOG_END, static_cast<float>(kPlaneGridHalf));
    glFogfv(GL_FOG_COLOR, lit);
    SetColor(kGridColor);
    DrawLines(PlaneGrid(m.plane, viewpoint.looked_at, kPlaneGridHalf, 1.0));
    glDisable(GL_FOG);
  } else if (!heightfield_) {
    // No ground at all (free fall worlds): grid lines through the origin
    // across up, for scale.
    const double plane[4] = {up.x(), up.y(), up.z(), 0};
    SetColor(kGridColor);
    DrawLines(PlaneGrid(plane, viewpoint.looked_at, 30, 1.0));
  }
  if (heightfield_ && !toggles.wireframe && !heightfield_grid_.positions.empty()) {
    SetColor(kFieldGridColor);
    DrawLines(heightfield_grid_);
  }
}

bool Renderer::RebuildRuts(const Scene& scene) {
  const auto now = std::chrono::steady_clock::now();
  bool any = false;
  for (int8_t ground : {soil_ruts_t::GROUND_PLANE, soil_ruts_t::GROUND_HEIGHTFIELD}) {
    const RutMap& ruts = scene.ruts(ground);
    RutLayer& layer = ruts_[static_cast<size_t>(ground)];
    // A cleared map (a new simulation) goes at once; growth waits its turn.
    if (ruts.generation() != layer.generation &&
        (ruts.cells() == 0 || !layer.floor || now - layer.built >= kRutRebuildInterval)) {
      layer.generation = ruts.generation();
      layer.built = now;
      layer.floor.reset();
      layer.opening.reset();
      // Ruts on the heightfield come only with a model that has one.
      const heightfield_t* field =
          ground == soil_ruts_t::GROUND_HEIGHTFIELD ? &scene.model().heightfield : nullptr;
      // A rut is its ground's colour, darkened (RutMesh).
      const Color ground = field != nullptr ? GroundColor(field_kind_) : plane_color_;
      if (ruts.cells() > 0) {
        layer.floor = std::make_unique<BufferMesh>(
            RutMesh(ruts, Eigen::Vector3f(ground[0], ground[1], ground[2]), field));
        layer.opening = std::make_unique<BufferMesh>(RutOpeningMesh(ruts, field));
      }
    }
    any = any || layer.floor;
  }
  return any;
}

void Renderer::DrawRuts(const Scene& scene) {
  if (!RebuildRuts(scene)) return;
  // Lowered below the ground, which would hide them. First the openings
  // on the ground, a little toward the camera, mark in the stencil where
  // they are seen (terrain before them fails the depth test); then the
  // floors are drawn there only, over the ground (the depth test always
  // passes) but writing their own depth, so that a wheel sunk in a rut
  // shows down to the rut's floor and the bodies drawn next hide it. A
  // rut's far edge faces the camera, its near edge away: culled, it does
  // not cover the floor. (The stencil is cleared with the frame; without
  // a stencil buffer the floors are drawn whole.)
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 1, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glDisable(GL_LIGHTING);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1, -4);
  for (const RutLayer& layer : ruts_)
    if (layer.opening) layer.opening->Draw();
  glDisable(GL_POLYGON_OFFSET_FILL);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilFunc(GL_EQUAL, 1, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glEnable(GL_LIGHTING);
  glEnable(GL_CULL_FACE);
  glDepthFunc(GL_ALWAYS);
  for (const RutLayer& layer : ruts_)
    if (layer.floor) layer.floor->Draw();
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
}

void Renderer::DrawBodies(const Scene& scene, const Toggles& toggles) {
  const model_t& m = scene.model();
  bodies_drawn_ = 0;
  if (toggles.wireframe) {
    glDisable(GL_LIGHTING);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glLineWidth(1);
  } else {
    glEnable(GL_LIGHTING);
  }
  for (int i = 0; i < m.num_bodies && i < static_cast<int>(body_lists_.size()); ++i) {
    if (body_lists_[static_cast<size_t>(i)] == 0) continue;
    const Eigen::Matrix4d pose = scene.BodyPose(i).matrix();
    glPushMatrix();
    glMultMatrixd(pose.data());
    Color c = BodyColor(m, i);
    if (toggles.wireframe)
      for (float& v : c) v *= 0.6f;  // darker lines read better on the sky
    SetColor(c);
    glCallList(body_lists_[static_cast<size_t>(i)]);
    glPopMatrix();
    ++bodies_drawn_;
  }
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void Renderer::DrawOverlays(const Scene& scene, const Viewpoint& viewpoint,
                            const Toggles& toggles) {
  const model_t& m = scene.model();
  const state_t* s = scene.state();
  const Eigen::Vector3d eye = viewpoint.eye;
  glDisable(GL_LIGHTING);
  glLineWidth(2);
  if (toggles.body_frames) {
    glBegin(GL_LINES);
    for (int i = 0; i < m.num_bodies; ++i) {
      const Eigen::Isometry3d pose = scene.BodyPose(i);
      const geometry_t& g = m.bodies[static_cast<size_t>(i)].geometry;
      const double length =
          std::clamp(0.75 * std::max({g.size[0], g.size[1], g.size[2]}), 0.1, 1.0);
      for (int axis = 0; axis < 3; ++axis) {
        Color c{0, 0, 0};
        c[static_cast<size_t>(axis)] = 1;
        SetColor(c);
        Vertex(pose.translation());
        Vertex(pose.translation() + length * pose.linear().col(axis));
      }
    }
    glEnd();
  }
  if (s != nullptr && toggles.contact_forces) {
    SetColor(kContactForceColor);
    for (int i = 0; i < s->num_bodies; ++i) {
      const body_state_t& b = s->bodies[static_cast<size_t>(i)];
      DrawArrow(V(b.position), kForceArrowScale * V(b.contact_force), eye);
    }
  }
  if (s != nullptr && toggles.joint_forces) {
    SetColor(kJointForceColor);
    for (int j = 0; j < s->num_joints; ++j) {
      const joint_state_t& js = s->joints[static_cast<size_t>(j)];
      DrawArrow(V(js.anchor), kForceArrowScale * V(js.force1), eye);
    }
  }
  if (toggles.scanner_rays) {
    for (const auto& [index, reading] : scene.scans()) {
      const sensor_t& sensor = m.sensors[static_cast<size_t>(index)];
      if (sensor.body < 0) continue;
      Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
      mount.linear() = Eigen::Quaterniond(sensor.orientation[0], sensor.orientation[1],
                                          sensor.orientation[2], sensor.orientation[3])
                           .normalized()
                           .toRotationMatrix();
      mount.translation() = V(sensor.position);
      const Eigen::Isometry3d world = scene.BodyPose(sensor.body) * mount;
      // params: rays, half-span [rad], range [m]; the reading's own count wins.
      const double half_span = sensor.num_params >= 2 ? sensor.params[1] : 0.1;
      const double range = sensor.num_params >= 3 ? sensor.params[2] : 10.0;
      const int rays = reading.num_values;
      std::vector<Eigen::Vector3d> hits;
      glBegin(GL_LINES);
      SetColor(kRayColor, 0.8f);
      for (int k = 0; k < rays; ++k) {
        // As the sim casts them: around the sensor's z axis in its z-x plane.
        const double angle = rays == 1 ? 0.0 : -half_span + 2.0 * half_span * k / (rays - 1);
        const Eigen::Vector3d direction =
            world.linear() * Eigen::Vector3d(std::sin(angle), 0.0, std::cos(angle));
        const double distance = reading.values[static_cast<size_t>(k)];
        const Eigen::Vector3d end = world.translation() + distance * direction;
        Vertex(world.translation());
        Vertex(end);
        if (distance < range * 0.9999) hits.push_back(end);
      }
      glEnd();
      glPointSize(6);
      glBegin(GL_POINTS);
      SetColor(kHitColor);
      for (const Eigen::Vector3d& h : hits) Vertex(h);
      glEnd();
    }
  }
  glLineWidth(1);
}

void Renderer::DrawText(const std::string& text, float x, float y, float scale, const Color& color,
                        float alpha) {
  const float w = kCellWidth * scale, h = kCellHeight * scale;
  const int glyphs = kLastGlyph - kFirstGlyph + 1;
  SetColor(color, alpha);
  glBegin(GL_QUADS);
  for (char ch : text) {
    if (ch < kFirstGlyph || ch > kLastGlyph) ch = '?';
    const float u0 = static_cast<float>(ch - kFirstGlyph) / glyphs;
    const float u1 = static_cast<float>(ch - kFirstGlyph + 1) / glyphs;
    glTexCoord2f(u0, 0);
    glVertex2f(x, y);
    glTexCoord2f(u1, 0);
    glVertex2f(x + w, y);
    glTexCoord2f(u1, 1);
    glVertex2f(x + w, y + h);
    glTexCoord2f(u0, 1);
    glVertex2f(x, y + h);
    x += w;
  }
  glEnd();
}

void Renderer::DrawHud(const Hud& hud, int width, int height) {
  // Pixel coordinates, y down.
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, width, height, 0, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  auto panel = [&](float x0, float y0, float x1, float y1, float alpha) {
    glDisable(GL_TEXTURE_2D);
    glColor4f(0.05f, 0.06f, 0.08f, alpha);
    glBegin(GL_QUADS);
    glVertex2f(x0, y0);
    glVertex2f(x1, y0);
    glVertex2f(x1, y1);
    glVertex2f(x0, y1);
    glEnd();
  };
  auto text_width = [](const std::string& t, float scale) {
    return static_cast<float>(t.size()) * kCellWidth * scale;
  };
  auto lines_panel = [&](const std::vector<HudLine>& lines, float y0) {
    float widest = 0;
    for (const HudLine& l : lines) widest = std::max(widest, text_width(l.text, kHudScale));
    panel(0, y0, widest + 16, y0 + lines.size() * kHudLineHeight + 6, 0.55f);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, font_texture_);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    float y = y0 + 5;
    for (const HudLine& l : lines) {
      DrawText(l.text, 8, y, kHudScale, l.color);
      y += kHudLineHeight;
    }
  };
  if (hud.inset) DrawInset(*hud.inset, width, height);
  if (!hud.top.empty()) lines_panel(hud.top, 0);
  if (!hud.bottom.empty())
    lines_panel(hud.bottom, height - hud.bottom.size() * kHudLineHeight - 6);
  if (!hud.key_help.empty()) {
    // Half size when the list does not fit the window at the HUD's size.
    float scale = kHudScale;
    auto widest_at = [&](float sc) {
      float widest = 0;
      for (const std::string& l : hud.key_help) widest = std::max(widest, text_width(l, sc));
      return widest;
    };
    const float line_height_2 = kCellHeight * kHudScale + 4;
    if (widest_at(kHudScale) + 24 > width || hud.key_help.size() * line_height_2 + 16 > height)
      scale = 1.0f;
    const float line_height = kCellHeight * scale + 2 * scale;
    const float widest = widest_at(scale);
    const float box_h = hud.key_help.size() * line_height + 16;
    const float x0 = std::max(0.0f, (width - widest) / 2 - 12);
    const float y0 = std::max(0.0f, (height - box_h) / 2);
    panel(x0, y0, x0 + widest + 24, y0 + box_h, 0.8f);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, font_texture_);
    float y = y0 + 8;
    for (const std::string& l : hud.key_help) {
      DrawText(l, x0 + 12, y, scale, {1, 1, 1});
      y += line_height;
    }
  }
  glDisable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, 0);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

void Renderer::DrawInset(const Inset& inset, int width, int height) {
  if (inset.width <= 0 || inset.height <= 0 || inset.rgb == nullptr) return;
  // A third of the window's width at most, never enlarged, in the corner.
  constexpr float kMargin = 8;
  const float scale = std::min(1.0f, width / 3.0f / inset.width);
  const float w = inset.width * scale, h = inset.height * scale;
  const float x0 = width - w - kMargin, y0 = height - h - kMargin;
  if (inset_texture_ == 0) glGenTextures(1, &inset_texture_);
  LoadTexture(inset_texture_, GL_LINEAR, GL_RGB, inset.width, inset.height, inset.rgb);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glBegin(GL_QUADS);  // the image's first row at the top
  glTexCoord2f(0, 0);
  glVertex2f(x0, y0);
  glTexCoord2f(1, 0);
  glVertex2f(x0 + w, y0);
  glTexCoord2f(1, 1);
  glVertex2f(x0 + w, y0 + h);
  glTexCoord2f(0, 1);
  glVertex2f(x0, y0 + h);
  glEnd();
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glBindTexture(GL_TEXTURE_2D, font_texture_);
  // At the font's own size, so that the label fits over the inset.
  DrawText(inset.label, x0, y0 - kCellHeight - 3, 1.0f, {1, 1, 1});
  glDisable(GL_TEXTURE_2D);
  glBindTexture(GL_TEXTURE_2D, 0);
}

namespace {

// glReadPixels of the current read buffer, rows turned top to bottom.
template <class T>
std::vector<T> ReadRows(int width, int height, GLenum format, GLenum type, int per_pixel) {
  const size_t row = static_cast<size_t>(width) * per_pixel;
  std::vector<T> bottom_up(row * height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, format, type, bottom_up.data());
  std::vector<T> rows(bottom_up.size());
  for (int y = 0; y < height; ++y)
    std::copy_n(bottom_up.data() + (height - 1 - y) * row, row, rows.data() + y * row);
  return rows;
}

}  // namespace

RgbImage ReadRgb(int width, int height) {
  RgbImage image;
  image.width = width;
  image.height = height;
  image.pixels = ReadRows<uint8_t>(width, height, GL_RGB, GL_UNSIGNED_BYTE, 3);
  return image;
}

std::vector<float> ReadDepth(int width, int height) {
  return ReadRows<float>(width, height, GL_DEPTH_COMPONENT, GL_FLOAT, 1);
}

RgbImage Renderer::ReadPixels(int width, int height) const {
  glReadBuffer(GL_BACK);
  return ReadRgb(width, height);
}

}  // namespace simpartner::viewer
