// OSMesa renderer (see renderer.h).
//
// OpenGL in the compatibility profile, every surface drawn with one shader program
// (SurfaceProgram: light per vertex, the texture filtered over each pixel's footprint),
// back faces culled: one display list per object compiled once, a mesh object's parts
// in buffer objects (MeshSurfaces), the terrain in chunks per material meshed at the
// detail the distance from the detail centre asks for (TerrainDetail), kept while it
// holds; textures uploaded once with mip chains and footprint layers built here
// (FootprintMips): the bytes do not depend on the driver. Each frame: cull chunks
// against the view frustum, draw near to far into a frame buffer object of one 8-bit
// channel, read it back flipped to top-down rows.
#include "trackbed/render/renderer.h"

#define GL_GLEXT_PROTOTYPES 1  // buffer objects (GL 1.5), which libOSMesa exports
#include <GL/gl.h>
#include <GL/osmesa.h>

#include <cstddef>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "edge_antialiasing.h"
#include "freed_memory.h"
#include "gl_primitives.h"
#include "ground_tiling.h"
#include "leaf_crown_drawing.h"
#include "luminaire.h"
#include "mesh_chunks.h"
#include "mesh_surfaces.h"
#include "object_albedo.h"
#include "sky_program.h"
#include "surface_program.h"
#include "texture_upload.h"
#include "track_mark_drawing.h"
#include "trackbed/common/option_error.h"
#include "trackbed/common/units.h"
#include "trackbed/render/car_model.h"
#include "trackbed/render/far_terrain.h"
#include "trackbed/render/object_detail.h"
#include "trackbed/render/procedural_texture.h"
#include "trackbed/render/terrain_detail.h"
#include "trackbed/render/terrain_window.h"

namespace trackbed::render {

namespace {

constexpr int kChunkCells = 16;

// A stable hash of an appearance name, to derive its texture's seed: FNV-1a's steps
// from another offset basis than procedural_texture.cpp's HashName (kept: every
// texture the renderer draws is seeded through it).
std::uint64_t TextureNameHash(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}

// A coarser version of an object, drawn from the distance where it departs from
// the full one by less than the bound in pixels.
struct FarVersion {
  GLuint list = 0;
  double departure_m = 0.0;  // how far its outline can depart from the full version's
};

struct Drawable {
  GLuint list = 0;                       // display list of an object, or
  int terrain = -1;                      // index of a terrain drawable, or
  int mesh = -1;                         // of a mesh object's part (mesh_surfaces.h)
  Eigen::AlignedBox3d box;               // world-frame bounds, for culling
  std::vector<FarVersion> far_versions;  // coarser and coarser
  bool curved = false;                   // a cylinder's outline: drawn antialiased
  GLuint band_list = 0;                  // the band about a curved object's outline
  bool flat = false;                     // a box or the ceiling: read by footprint
  GLuint leaf_list = 0;                  // a tree's crown of leaf cards (leaf_crown_drawing.h)
};

// A texture as uploaded: GL name and world size of one repeat.
struct GlTexture {
  GLuint name = 0;
  double meters_per_repeat = 1.0;
  bool ground = false;  // with the layers for long footprints
  bool tiled = false;   // a ground's variants, drawn tiled stochastically (ground_tiling.h)
  TileVariation tiling;
  std::uint32_t tiling_seed = 0;
};

// Directions of the footprint layers of a ground's texture (footprint_mips.h).
constexpr int kFootprintDirections = 16;

// One material of one terrain chunk, and its mesh for the last detail centre; or
// one piece of the far terrain, its mesh fixed.
struct TerrainDrawable {
  std::size_t chunk = 0;
  bool fixed = false;  // a far terrain piece
  GlTexture texture;
  TerrainDetail::Mesh mesh;
  Eigen::Vector2d center_xy = Eigen::Vector2d::Zero();
  bool built = false;
  // Buffer objects holding the mesh: Mesa copies client-side arrays and scans
  // their indices on every draw call.
  GLuint vertex_buffer = 0, index_buffer = 0;
  int uploaded_topology = -1;
  GLsizei index_count = 0;
  GLsizeiptr vertex_bytes = 0;    // size of the vertex buffer's storage
  std::vector<MeshLevel> levels;  // a mesh chunk's versions, full first (mesh_far_versions.h)
};

// Frustum culling in camera coordinates: false when all the box's corners are outside
// one of the six planes of the view of K from T_camera_world.
bool InFrustum(const Eigen::AlignedBox3d& box, const geometry::PinholeCamera& K,
               const Eigen::Isometry3d& T_camera_world, double near_m, double far_m) {
  const double w = K.width_px, h = K.height_px;
  int outside[6] = {0, 0, 0, 0, 0, 0};
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p =
        T_camera_world * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    const double X = p.x(), Y = p.y(), Z = p.z();
    outside[0] += (K.fx * X + (K.cx + 0.5) * Z < 0);
    outside[1] += (-K.fx * X + (w - 0.5 - K.cx) * Z < 0);
    outside[2] += (K.fy * Y + (K.cy + 0.5) * Z < 0);
    outside[3] += (-K.fy * Y + (h - 0.5 - K.cy) * Z < 0);
    outside[4] += (Z < near_m);
    outside[5] += (Z > far_m);
  }
  return std::none_of(std::begin(outside), std::end(outside), [](int n) { return n == 8; });
}

}  // namespace

struct Renderer::Gl {
  OSMesaContext context = nullptr;
  int width = 0, height = 0;
  double near_m = 0.05, far_m = 100.0;
  SceneAppearance appearance;
  std::uint64_t seed = 0;
  const sim::Terrain* terrain = nullptr;
  // OSMesa's own frame buffer, 1 x 1 and never drawn into: the frame buffer
  // object (one 8-bit channel and depth) is what is drawn and read, so the
  // shaders write one byte per pixel and OSMesa copies nothing at glFinish.
  std::vector<std::uint8_t> osmesa_pixel = std::vector<std::uint8_t>(4, 0);
  std::unique_ptr<EdgeAntialiasing> target;  // the frame buffers drawn and read
  std::vector<std::uint8_t> grey;            // read back, bottom row first
  std::vector<float> depth;
  std::map<std::string, GlTexture> textures;
  std::map<std::string, GlTexture> tiled_textures;  // grounds of the detailed look
  std::vector<Drawable> drawables;
  std::unique_ptr<TerrainWindow> window;              // which part of the grid is near
  std::optional<TerrainWindow::Placement> placement;  // where it is now
  std::unique_ptr<TerrainDetail> detail;              // the near window's levels
  std::vector<TerrainDrawable> terrain_drawables;
  std::size_t terrain_drawable_count = 0;       // drawables[0, count) are the terrain's
  std::vector<TerrainDrawable> mesh_drawables;  // mesh objects' chunks (fixed)
  std::size_t mesh_triangles = 0;               // of mesh objects, drawn in this frame
  std::vector<sim::OccluderSpec> occluders;
  std::vector<GLuint> occluder_lists;
  std::vector<std::pair<double, int>> draw_order;  // per frame, kept to avoid reallocation
  std::unique_ptr<SurfaceProgram> program;         // draws every surface
  std::unique_ptr<SkyProgram> sky;                 // a sky not flat
  std::unique_ptr<LeafCrowns> leaf_crowns;         // crowns of leaf cards
  bool lit = false;                                // with scene lighting: pre-exposed
  std::vector<ShadowBox> robot_boxes;              // the robot's shadow's boxes, body frame
  Eigen::Isometry3d T_world_robot = Eigen::Isometry3d::Identity();
  double exposure = 1.0;  // what a lit render is pre-exposed for

  ~Gl() {
    if (context) OSMesaDestroyContext(context);
  }

  void MakeCurrent() {
    if (!OSMesaMakeCurrent(context, osmesa_pixel.data(), GL_UNSIGNED_BYTE, 1, 1)) {
      throw std::runtime_error("Renderer: OSMesaMakeCurrent failed");
    }
    if (target) target->BindForDrawing();
  }

  // The frame's grey levels and depths, top row first. Reading the frame buffer object
  // waits for llvmpipe to finish the frame.
  void ReadBack(GrayImage* gray_out, DepthImage* depth_out) {
    const int W = width, H = height;
    target->Resolve();
    if (gray_out) {
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, W, H, GL_RED, GL_UNSIGNED_BYTE, grey.data());
      gray_out->width = W;
      gray_out->height = H;
      gray_out->pixels.resize(static_cast<std::size_t>(W) * H);
      for (int v = 0; v < H; ++v) {  // OpenGL's first row is the bottom one
        std::copy_n(&grey[static_cast<std::size_t>(H - 1 - v) * W], W,
                    &gray_out->pixels[static_cast<std::size_t>(v) * W]);
      }
    }
    if (depth_out) {
      glPixelStorei(GL_PACK_ALIGNMENT, 4);
      glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
      depth_out->width = W;
      depth_out->height = H;
      depth_out->depth_m.resize(static_cast<std::size_t>(W) * H);
      for (int v = 0; v < H; ++v) {
        const float* src = &depth[static_cast<std::size_t>(H - 1 - v) * W];
        float* dst = &depth_out->depth_m[static_cast<std::size_t>(v) * W];
        for (int u = 0; u < W; ++u) {
          dst[u] = static_cast<float>(DepthFromBuffer(src[u], near_m, far_m));
        }
      }
    }
  }

  // The texture of an appearance, made and uploaded when first asked for; a ground's
  // (`ground`) with the layers for long footprints (footprint_mips.h), which an
  // object's is made without and gains when a ground asks for it too.
  const GlTexture& Texture(const std::string& name, double fallback_albedo = 0.5,
                           bool ground = false) {
    auto it = textures.find(name);
    if (it != textures.end() && (it->second.ground || !ground)) return it->second;
    if (it == textures.end()) {
      GlTexture g;
      glGenTextures(1, &g.name);
      it = textures.emplace(name, g).first;
    }
    const std::uint64_t s = seed ^ TextureNameHash(name);
    const render::Texture t = HasTexture(name) ? MakeTexture(name, s, appearance.texture_size_px)
                                               : MakePlainTexture(fallback_albedo, s, 64);
    it->second.meters_per_repeat = t.meters_per_repeat;
    it->second.ground = ground;
    UploadTexture(it->second, {t});
    return it->second;
  }

  // An object's texture: a plain one of its own albedo where it has one (object_albedo.h).
  const GlTexture& ObjectTexture(const sim::StaticObject& o, bool ground = false) {
    return o.albedo ? Texture(AlbedoTextureName(*o.albedo), *o.albedo, ground)
                    : Texture(o.appearance, 0.5, ground);
  }

  // A terrain material's texture: its variants, tiled, under the detailed look; else Texture's.
  const GlTexture& GroundTexture(const sim::TerrainMaterial& m) {
    const bool detailed = appearance.ground_look == GroundLook::kDetailed;
    if (!DetailedLook(detailed, appearance.classic_look_materials, m.name)) {
      return Texture(m.name, m.albedo, true);
    }
    auto it = tiled_textures.find(m.name);
    if (it != tiled_textures.end()) return it->second;
    const std::uint64_t s = seed ^ TextureNameHash(m.name);
    const auto variants = MakeTextureVariants(m.name, s, appearance.texture_size_px);
    GlTexture g{0,    variants.front().meters_per_repeat, true,
                true, GroundTileVariation(m.name),        TilingSeed(s)};
    glGenTextures(1, &g.name);
    UploadTexture(g, variants);
    return tiled_textures.emplace(m.name, g).first->second;
  }

  // Puts the textures `ts` into texture `g` (texture_upload.h): a ground's with the
  // footprint layers' directions.
  static void UploadTexture(const GlTexture& g, const std::vector<render::Texture>& ts) {
    UploadFootprintTexture(g.name, g.ground ? kFootprintDirections : 0, ts);
  }

  // Terrain drawables, first in `drawables`: one per (chunk, material) of the near
  // window, meshed per frame from the detail centre (TerrainDetail), the mesh kept
  // while it still holds; one per piece of the far terrain beyond a paged window.
  void BuildTerrain(const GridWindow& w) {
    ReleaseTerrain();
    detail =
        std::make_unique<TerrainDetail>(*terrain, appearance.terrain_full_detail_m, kChunkCells, w);
    std::vector<Drawable> boxes;
    for (std::size_t c = 0; c < detail->chunks().size(); ++c) {
      const TerrainDetail::Chunk& chunk = detail->chunks()[c];
      const sim::TerrainMaterial& material = terrain->materials()[chunk.material];
      TerrainDrawable t;
      t.chunk = c;
      t.texture = GroundTexture(material);
      terrain_drawables.push_back(std::move(t));
      Drawable d;
      d.box = chunk.box;
      d.terrain = static_cast<int>(terrain_drawables.size()) - 1;
      boxes.push_back(d);
    }
    if (window->paged()) BuildFarTerrain(w, &boxes);
    drawables.insert(drawables.begin(), boxes.begin(), boxes.end());
    terrain_drawable_count = boxes.size();
  }

  void BuildFarTerrain(const GridWindow& w, std::vector<Drawable>* boxes) {
    std::vector<double> meters_per_repeat;
    for (const sim::TerrainMaterial& m : terrain->materials()) {
      meters_per_repeat.push_back(GroundTexture(m).meters_per_repeat);
    }
    FarTerrain far(*terrain, w, far_m, meters_per_repeat);
    for (const FarTerrain::Piece& piece : far.pieces()) {
      const sim::TerrainMaterial& material = terrain->materials()[piece.material];
      TerrainDrawable t;
      t.fixed = true;
      t.texture = GroundTexture(material);
      t.mesh.vertices = piece.vertices;
      t.mesh.indices = piece.indices;
      t.mesh.level = TerrainDetail::kMaxLevel;
      t.mesh.topology = 0;
      terrain_drawables.push_back(std::move(t));
      Drawable d;
      d.box = piece.box;
      d.terrain = static_cast<int>(terrain_drawables.size()) - 1;
      boxes->push_back(d);
    }
  }

  void ReleaseTerrain() {
    for (TerrainDrawable& t : terrain_drawables) {
      if (t.vertex_buffer != 0) {
        glDeleteBuffers(1, &t.vertex_buffer);
        glDeleteBuffers(1, &t.index_buffer);
      }
    }
    terrain_drawables.clear();
    drawables.erase(drawables.begin(),
                    drawables.begin() + static_cast<std::ptrdiff_t>(terrain_drawable_count));
    terrain_drawable_count = 0;
  }

  // Moves the near window to the detail centre when it must (a paged terrain).
  void FollowDetailCenter(const Eigen::Vector2d& center_xy) {
    std::optional<TerrainWindow::Placement> next = window->Follow(center_xy, placement);
    if (!next) return;
    placement = next;
    BuildTerrain(next->window);
  }

  // Puts the mesh into the drawable's buffer objects.
  static void Upload(TerrainDrawable& t) {
    if (t.vertex_buffer == 0) {
      glGenBuffers(1, &t.vertex_buffer);
      glGenBuffers(1, &t.index_buffer);
    }
    // A mesh of the same size overwrites the buffer's storage: glBufferData
    // would have Mesa free and allocate it anew on every re-mesh (and glibc
    // hand the memory back and fault it in again; docs/rendering.md).
    const auto bytes = static_cast<GLsizeiptr>(t.mesh.vertices.size() * sizeof(TerrainVertex));
    glBindBuffer(GL_ARRAY_BUFFER, t.vertex_buffer);
    if (bytes == t.vertex_bytes) {
      glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, t.mesh.vertices.data());
    } else {
      glBufferData(GL_ARRAY_BUFFER, bytes, t.mesh.vertices.data(), GL_DYNAMIC_DRAW);
      t.vertex_bytes = bytes;
    }
    if (t.mesh.topology != t.uploaded_topology) {
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, t.index_buffer);
      glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(t.mesh.indices.size() * sizeof(std::uint32_t)),
                   t.mesh.indices.data(), GL_DYNAMIC_DRAW);
      t.uploaded_topology = t.mesh.topology;
      t.index_count = static_cast<GLsizei>(t.mesh.indices.size());
    }
  }

  // The terrain's mesh, or the version `level` of a mesh chunk's.
  void DrawTerrain(TerrainDrawable& t, const Eigen::Vector2d& center_xy,
                   const MeshLevel* level = nullptr) {
    if (t.fixed) {
      if (!t.built) {
        Upload(t);
        t.mesh.vertices = {};  // the buffer objects hold them now
        t.mesh.indices = {};
      }
      t.built = true;
    } else {
      const TerrainDetail::Chunk& chunk = detail->chunks()[t.chunk];
      if (!t.built ||
          (center_xy != t.center_xy && !detail->SameMesh(chunk, t.center_xy, center_xy))) {
        detail->BuildMesh(chunk, center_xy, t.texture.meters_per_repeat, &t.mesh);
        t.center_xy = center_xy;
        t.built = true;
        Upload(t);
      }
    }
    const GLsizei count = level ? static_cast<GLsizei>(level->index_count) : t.index_count;
    if (count == 0) return;
    if (level) mesh_triangles += static_cast<std::size_t>(count) / 3;
    glBindTexture(GL_TEXTURE_2D_ARRAY, t.texture.name);
    glBindBuffer(GL_ARRAY_BUFFER, t.vertex_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, t.index_buffer);
    const auto offset = [](std::size_t bytes) { return reinterpret_cast<const void*>(bytes); };
    glVertexPointer(3, GL_FLOAT, sizeof(TerrainVertex), offset(offsetof(TerrainVertex, x)));
    glNormalPointer(GL_FLOAT, sizeof(TerrainVertex), offset(offsetof(TerrainVertex, nx)));
    glTexCoordPointer(2, GL_FLOAT, sizeof(TerrainVertex), offset(offsetof(TerrainVertex, s)));
    glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT,
                   offset(level ? level->first_index * sizeof(std::uint32_t) : 0));
  }

  // The pixels the outlines of curved objects cross: the bands about them, far to near,
  // blended over what is behind by the fraction of each pixel inside; then their depth
  // where more than half inside (surface_program.h).
  void DrawOutlineFringes(const std::vector<std::pair<double, int>>& order) {
    glDisable(GL_CULL_FACE);    // the bands' winding follows the view
    glDisable(GL_MULTISAMPLE);  // their coverage is computed: every sample as the centre
    program->Use(SurfaceProgram::Kind::kOutlineFringe);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LEQUAL);
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
      const Drawable& d = drawables[static_cast<std::size_t>(it->second)];
      if (d.curved) glCallList(d.band_list);
    }
    if (leaf_crowns) leaf_crowns->Draw(LeafCrowns::Pass::kFringe, order, drawables);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    program->Use(SurfaceProgram::Kind::kOutlineDepth);
    for (const auto& [distance, k] : order) {
      const Drawable& d = drawables[static_cast<std::size_t>(k)];
      if (d.curved) glCallList(d.band_list);
    }
    if (leaf_crowns) leaf_crowns->Draw(LeafCrowns::Pass::kDepth, order, drawables);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_MULTISAMPLE);
    glEnable(GL_CULL_FACE);
  }

  // The version of an object to draw: the coarsest whose silhouette departs from
  // the full one's by less than `object_far_error_px`, seen from the detail centre at
  // the distance of the object's nearest side (so both cameras of a pair draw the same).
  GLuint ObjectList(const Drawable& d, double focal_px,
                    const Eigen::Vector2d& detail_center_xy) const {
    if (d.far_versions.empty()) return d.list;
    const Eigen::Vector2d center = d.box.center().head<2>();
    const double reach = 0.5 * d.box.sizes().head<2>().maxCoeff();
    const double distance = (center - detail_center_xy).norm() - reach;
    GLuint list = d.list;
    for (const FarVersion& v : d.far_versions) {
      if (distance < FarVersionDistance(v.departure_m, focal_px, appearance.object_far_error_px))
        break;
      list = v.list;
    }
    return list;
  }

  // Objects of kind "tree" drawn as cylinders: the trunks that carry a crown (when
  // crowns are drawn) and have far versions.
  static bool IsTree(const sim::StaticObject& o) {
    return o.kind == "tree" && o.shape == sim::StaticObject::Shape::kCylinder;
  }
  bool DrawsCrown(const sim::StaticObject& o) const { return IsTree(o) && appearance.tree_crowns; }
  bool SphereCrown(const sim::StaticObject& o) const { return DrawsCrown(o) && !leaf_crowns; }

  // One object's display list; a tree's with the facets of `level`. Its textures
  // are made before the list is compiled: made inside it, their upload would be
  // compiled into the list instead of done.
  GLuint CompileObject(const sim::StaticObject& o, const TreeTessellation& level) {
    // A box's faces (walls, seen at grazing angles) read by footprint, as the ground.
    const bool flat = o.shape == sim::StaticObject::Shape::kBox;
    const GlTexture& tex = ObjectTexture(o, flat);
    const std::vector<CarPart> parts =
        flat && o.kind == "car" ? CarParts(o.size_m) : std::vector<CarPart>{};
    for (const CarPart& p : parts) PartTexture(o, p);
    const bool crown = SphereCrown(o);
    const GlTexture& leaves = crown ? Texture("leaves") : tex;
    const GLuint list = glGenLists(1);
    glNewList(list, GL_COMPILE);
    glBindTexture(GL_TEXTURE_2D_ARRAY, tex.name);
    glPushMatrix();
    glTranslated(o.center_m.x(), o.center_m.y(), o.base_z_m);
    if (!parts.empty()) {
      glRotated(units::Degrees(o.yaw_rad), 0, 0, 1);
      DrawCarParts(o, parts);
    } else if (o.shape == sim::StaticObject::Shape::kBox) {
      glRotated(units::Degrees(o.yaw_rad), 0, 0, 1);
      glTranslated(0, 0, o.size_m.z() / 2);
      (o.kind == "luminaire" ? DrawLuminaire : DrawBox)(o.size_m, tex.meters_per_repeat);
    } else {
      glMultiTexCoord4d(GL_TEXTURE1, 0, 0, 0, -o.radius_m);  // the outline's shape
      DrawCylinder(o.radius_m, o.height_m, tex.meters_per_repeat, level.trunk_slices);
      if (crown) {
        // Visual-only foliage: a crown a third of the trunk's height across.
        glBindTexture(GL_TEXTURE_2D_ARRAY, leaves.name);
        glTranslated(0, 0, o.height_m);
        glMultiTexCoord4d(GL_TEXTURE1, 0, 0, 0, TreeCrownRadius(o));
        DrawSphere(TreeCrownRadius(o), leaves.meters_per_repeat, level.crown_slices,
                   level.crown_stacks);
      }
    }
    glPopMatrix();
    glEndList();
    return list;
  }

  // A car part's texture (car_model.h): the car's own for its painted parts.
  const GlTexture& PartTexture(const sim::StaticObject& o, const CarPart& p) {
    return p.appearance.empty() ? Texture(o.appearance, 0.5, true)
                                : Texture(p.appearance, p.albedo, true);
  }

  void DrawCarParts(const sim::StaticObject& o, const std::vector<CarPart>& parts) {
    for (const CarPart& p : parts) {
      const GlTexture& t = PartTexture(o, p);
      glBindTexture(GL_TEXTURE_2D_ARRAY, t.name);
      if (p.shape == CarPart::Shape::kWheel) {
        glPushMatrix();
        glTranslated(p.center.x(), p.center.y(), p.center.z());
        DrawWheel(p.radius, p.width, p.side, t.meters_per_repeat);
        glPopMatrix();
      } else {
        DrawPrism(p.x0, p.x1, p.top_x0, p.top_x1, p.half_width, p.top_half_width, p.z0, p.z1,
                  t.meters_per_repeat);
      }
    }
  }

  // The display list of the bands about a cylinder object's outlines (its trunk's and
  // its crown's), in the vertices the band program reads (surface_program.cpp): each
  // band's shape on texture unit 1, its texture's repeat and a cylinder's height on
  // unit 2, where each vertex lies on the band on unit 0.
  GLuint CompileBands(const sim::StaticObject& o) {
    const GlTexture& tex = ObjectTexture(o);
    const bool crown = SphereCrown(o);
    const GlTexture& leaves = crown ? Texture("leaves") : tex;
    const GLuint list = glGenLists(1);
    glNewList(list, GL_COMPILE);
    glBindTexture(GL_TEXTURE_2D_ARRAY, tex.name);
    glPushMatrix();
    glTranslated(o.center_m.x(), o.center_m.y(), o.base_z_m);
    glMultiTexCoord4d(GL_TEXTURE1, 0, 0, 0, -o.radius_m);
    glMultiTexCoord4d(GL_TEXTURE2, 1.0 / tex.meters_per_repeat, o.height_m, 0, 0);
    glBegin(GL_QUADS);
    for (double side : {-1.0, 1.0}) {
      for (const auto& [end, edge] : {std::pair{-1.0, -1.0}, std::pair{-1.0, 1.0},
                                      std::pair{1.0, 1.0}, std::pair{1.0, -1.0}}) {
        glMultiTexCoord4d(GL_TEXTURE0, side, end, edge, 0);
        glVertex3d(0, 0, end > 0 ? o.height_m : 0.0);
      }
    }
    glEnd();
    if (crown) {
      glBindTexture(GL_TEXTURE_2D_ARRAY, leaves.name);
      glMultiTexCoord4d(GL_TEXTURE1, 0, 0, o.height_m, TreeCrownRadius(o));
      glMultiTexCoord4d(GL_TEXTURE2, 1.0 / leaves.meters_per_repeat, 0, 0, 0);
      glBegin(GL_QUAD_STRIP);
      for (int k = 0; k <= kOutlineRingSegments; ++k) {
        const double a = 2 * M_PI * k / kOutlineRingSegments;
        for (double edge : {-1.0, 1.0}) {
          glMultiTexCoord4d(GL_TEXTURE0, std::cos(a), std::sin(a), edge, 0);
          glVertex3d(0, 0, o.height_m);
        }
      }
      glEnd();
    }
    glPopMatrix();
    glEndList();
    return list;
  }

  // World-frame bounds of an object as drawn, crown included.
  Eigen::AlignedBox3d DrawnBounds(const sim::StaticObject& o) const {
    if (o.shape == sim::StaticObject::Shape::kBox) {
      const double r = 0.5 * o.size_m.head<2>().norm();
      return Eigen::AlignedBox3d(
          Eigen::Vector3d(o.center_m.x() - r, o.center_m.y() - r, o.base_z_m),
          Eigen::Vector3d(o.center_m.x() + r, o.center_m.y() + r, o.base_z_m + o.size_m.z()));
    }
    double top = o.height_m, reach = o.radius_m;
    if (DrawsCrown(o)) {
      top += TreeCrownRadius(o);
      reach = std::max(reach, TreeCrownRadius(o));
    }
    return Eigen::AlignedBox3d(
        Eigen::Vector3d(o.center_m.x() - reach, o.center_m.y() - reach, o.base_z_m),
        Eigen::Vector3d(o.center_m.x() + reach, o.center_m.y() + reach, o.base_z_m + top));
  }

  // One drawable per chunk of a part of a mesh object (mesh_chunks.h), read by footprint
  // as the ground and boxes; with far versions where objects have them.
  void BuildMeshes(const sim::World& world) {
    for (const sim::MeshObject& m : world.meshes()) {
      const std::optional<double>& albedo = m.entry.albedo;
      for (MeshChunk& s : MeshChunks(m, appearance.object_far_error_px > 0.0)) {
        const std::string key = albedo ? "mesh " + AlbedoTextureName(*albedo) : s.texture_key;
        auto it = textures.find(key);
        if (it == textures.end()) {
          GlTexture g;
          g.ground = true;
          glGenTextures(1, &g.name);
          UploadTexture(g, {albedo ? MakePlainTexture(*albedo, seed ^ TextureNameHash(key), 64)
                                   : MeshPartTexture(*s.part)});
          it = textures.emplace(key, g).first;
        }
        TerrainDrawable t;
        t.fixed = true;
        t.texture = it->second;
        t.mesh.vertices = std::move(s.vertices);
        t.mesh.indices = std::move(s.indices);
        t.mesh.topology = 0;
        t.levels = std::move(s.levels);
        mesh_drawables.push_back(std::move(t));
        Drawable d;
        d.box = s.box;
        d.mesh = static_cast<int>(mesh_drawables.size()) - 1;
        drawables.push_back(d);
      }
    }
  }

  void BuildObjects(const sim::World& world) {
    for (const sim::StaticObject& o : world.objects()) {
      Drawable d;
      d.list = CompileObject(o, kTreeLevels[0]);
      d.box = DrawnBounds(o);
      d.curved = o.shape == sim::StaticObject::Shape::kCylinder;
      if (d.curved) d.band_list = CompileBands(o);
      if (DrawsCrown(o) && leaf_crowns)
        d.leaf_list = leaf_crowns->Compile(o, TreeCrownRadius(o), seed);
      d.flat = o.shape == sim::StaticObject::Shape::kBox;
      if (IsTree(o) && appearance.object_far_error_px > 0.0) {
        const double crown = SphereCrown(o) ? TreeCrownRadius(o) : 0.0;
        for (std::size_t l = 1; l < kTreeLevels.size(); ++l) {
          d.far_versions.push_back({CompileObject(o, kTreeLevels[l]),
                                    TreeLevelDeparture(crown, o.radius_m, kTreeLevels[l])});
        }
      }
      drawables.push_back(d);
    }
    if (appearance.ceiling_height_m > 0.0) {
      const sim::Terrain& t = *terrain;
      const GlTexture& tex = Texture("ceiling", 0.5, true);
      const double z = appearance.ceiling_height_m, m = tex.meters_per_repeat;
      Drawable d;
      d.flat = true;
      d.box = Eigen::AlignedBox3d(Eigen::Vector3d(t.x_min(), t.y_min(), z),
                                  Eigen::Vector3d(t.x_max(), t.y_max(), z));
      d.list = glGenLists(1);
      glNewList(d.list, GL_COMPILE);
      glBindTexture(GL_TEXTURE_2D_ARRAY, tex.name);
      glBegin(GL_QUADS);
      // Clockwise seen from above: the front face, and its normal, look down,
      // so the sun above does not light the underside.
      glNormal3d(0, 0, -1);
      for (const auto& [x, y] :
           {std::pair{t.x_min(), t.y_min()}, std::pair{t.x_min(), t.y_max()},
            std::pair{t.x_max(), t.y_max()}, std::pair{t.x_max(), t.y_min()}}) {
        glTexCoord2d(x / m, y / m);
        glVertex3d(x, y, z);
      }
      glEnd();
      glEndList();
      drawables.push_back(d);
    }
    for (const sim::OccluderSpec& o : occluders) {
      // A person: body cylinder to shoulder height, a head above it.
      const GlTexture& tex = Texture(o.appearance);
      const GLuint list = glGenLists(1);
      glNewList(list, GL_COMPILE);
      glBindTexture(GL_TEXTURE_2D_ARRAY, tex.name);
      const double head = std::min(0.12, 0.07 * o.height_m);
      DrawCylinder(o.radius_m, o.height_m - 2 * head, tex.meters_per_repeat);
      glTranslated(0, 0, o.height_m - head);
      DrawSphere(head, tex.meters_per_repeat);
      glEndList();
      occluder_lists.push_back(list);
    }
  }
};

Renderer::Renderer(const sim::World& world, const SceneAppearance& appearance,
                   std::vector<sim::OccluderSpec> occluders, std::uint64_t seed, int width_px,
                   int height_px, double near_m, double far_m, int edge_samples)
    : gl_(std::make_unique<Gl>()) {
  appearance.Validate();
  KeepFreedMemory();
  for (std::size_t k = 0; k < occluders.size(); ++k) {
    option_check::Nested("occluders[" + std::to_string(k) + "]", occluders[k]);
  }
  if (width_px < 16 || height_px < 16 || width_px > 8192 || height_px > 8192) {
    throw std::invalid_argument("Renderer: image size must be in [16, 8192] pixels");
  }
  if (!(near_m > 0 && far_m > near_m)) {
    throw std::invalid_argument("Renderer: need 0 < near_m < far_m");
  }
  Gl& g = *gl_;
  g.width = width_px;
  g.height = height_px;
  g.near_m = near_m;
  g.far_m = far_m;
  g.appearance = appearance;
  g.seed = seed;
  g.terrain = &world.terrain();
  g.occluders = std::move(occluders);
  g.grey.resize(static_cast<std::size_t>(width_px) * height_px);
  g.depth.resize(static_cast<std::size_t>(width_px) * height_px);
  g.context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!g.context) throw std::runtime_error("Renderer: OSMesaCreateContextExt failed");
  g.MakeCurrent();
  g.target = std::make_unique<EdgeAntialiasing>(width_px, height_px, edge_samples);

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // Dithering (on by default) changes no byte of the 8-bit images, but llvmpipe
  // pays for it per fragment: off, rendering is 1.03-1.13x faster
  // (docs/rendering.md).
  glDisable(GL_DITHER);
  // Every surface is wound counter-clockwise seen from outside (terrain from
  // above, the ceiling from below), so back faces are hidden ones: culling
  // them spares llvmpipe rasterizing them (docs/rendering.md has the speed-up).
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  const float sky = static_cast<float>(appearance.sky_gray);
  glClearColor(sky, sky, sky, 1.0f);

  // A terrain that fits in the near window is built now; a paged one's window
  // follows the detail centre from the first frame.
  g.window = std::make_unique<TerrainWindow>(*g.terrain, appearance.terrain_full_detail_m);
  if (!g.window->paged()) g.FollowDetailCenter(Eigen::Vector2d::Zero());
  if (appearance.crowns == CrownLook::kLeaves)
    g.leaf_crowns = std::make_unique<LeafCrowns>(seed, appearance.ambient, appearance.diffuse);
  g.BuildObjects(world);
  g.BuildMeshes(world);
  std::optional<LightMap> light_map;
  if (appearance.lighting) {
    const Eigen::Vector3d sun =
        SunDirection(appearance.sun_azimuth_deg, appearance.sun_elevation_deg);
    light_map = BakeLightMap(world, *appearance.lighting, sun, appearance.tree_crowns);
  }
  g.lit = light_map.has_value();
  g.program =
      std::make_unique<SurfaceProgram>(light_map ? &*light_map : nullptr, appearance.ambient,
                                       appearance.diffuse, appearance.robot_shadow);
  if (appearance.sky != SkyLook::kFlat) g.sky = std::make_unique<SkyProgram>(appearance.sky, seed);
  if (glGetError() != GL_NO_ERROR)
    throw std::runtime_error("Renderer: OpenGL error while building");
}

Renderer::~Renderer() = default;

bool Renderer::pre_exposed() const { return gl_->lit; }

std::size_t Renderer::mesh_triangles_submitted() const { return gl_->mesh_triangles; }

void Renderer::SetExposure(double exposure) {
  if (!gl_->lit) throw std::logic_error("Renderer::SetExposure: the scene has no lighting");
  if (!(std::isfinite(exposure) && exposure > 0.0)) {
    throw std::invalid_argument("Renderer::SetExposure: exposure must be > 0");
  }
  gl_->exposure = exposure;
}

void Renderer::ReplaceTexture(const std::string& appearance, const Texture& texture) {
  auto it = gl_->textures.find(appearance);
  if (it == gl_->textures.end()) return;
  if (texture.meters_per_repeat != it->second.meters_per_repeat) {
    throw std::invalid_argument("Renderer::ReplaceTexture: '" + appearance + "' repeats every " +
                                std::to_string(it->second.meters_per_repeat) +
                                " m, the texture every " +
                                std::to_string(texture.meters_per_repeat));
  }
  gl_->MakeCurrent();
  Gl::UploadTexture(it->second, {texture});
}

void Renderer::SetRobotShape(std::vector<ShadowBox> boxes_body) {
  if (!boxes_body.empty()) MakeShadowFrame(boxes_body, {}, Eigen::Matrix4d::Identity(), {0, 0, 1});
  gl_->robot_boxes = std::move(boxes_body);
}

void Renderer::SetRobotPose(const Eigen::Isometry3d& T_world_body) {
  gl_->T_world_robot = T_world_body;
}

std::string Renderer::gl_description() const {
  gl_->MakeCurrent();
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(renderer ? renderer : "?") + " / " + (version ? version : "?");
}

void Renderer::Render(const geometry::PinholeCamera& K, const Eigen::Isometry3d& T_world_camera,
                      double t_s, GrayImage* gray, DepthImage* depth,
                      const Eigen::Vector2d* detail_center_xy) {
  Gl& g = *gl_;
  if (K.width_px != g.width || K.height_px != g.height) {
    throw std::invalid_argument("Renderer::Render: intrinsics are for " +
                                std::to_string(K.width_px) + "x" + std::to_string(K.height_px) +
                                ", the renderer draws " + std::to_string(g.width) + "x" +
                                std::to_string(g.height));
  }
  g.MakeCurrent();
  glViewport(0, 0, g.width, g.height);
  if (g.lit) {  // the sky pre-exposed too
    const float sky = static_cast<float>(std::min(g.appearance.sky_gray * g.exposure, 1.0));
    glClearColor(sky, sky, sky, 1.0f);
  }
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  const Eigen::Matrix4d P = OpenGlProjection(K, g.near_m, g.far_m);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(P.data());
  // OpenGL eye axes from OpenCV camera axes: flip y and z.
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.row(1) *= -1.0;
  view.row(2) *= -1.0;
  const Eigen::Isometry3d T_camera_world = T_world_camera.inverse();
  view = view * T_camera_world.matrix();
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(view.data());
  const Eigen::Vector3d sun_world =
      SunDirection(g.appearance.sun_azimuth_deg, g.appearance.sun_elevation_deg);
  std::optional<ShadowFrame> shadow;
  if (g.appearance.robot_shadow && !g.robot_boxes.empty()) {
    shadow = MakeShadowFrame(g.robot_boxes, g.T_world_robot, view, sun_world);
  }
  g.program->Begin(view, sun_world, g.lit ? g.exposure : 1.0, K, shadow ? &*shadow : nullptr);

  const Eigen::Matrix3d R = T_camera_world.linear();
  const Eigen::Vector3d tr = T_camera_world.translation();
  const Eigen::Vector2d center_xy =
      detail_center_xy ? *detail_center_xy : T_world_camera.translation().head<2>();
  g.FollowDetailCenter(center_xy);
  // Near to far, so that llvmpipe's early depth test rejects hidden fragments
  // before they are textured.
  std::vector<std::pair<double, int>>& order = g.draw_order;
  order.clear();
  g.mesh_triangles = 0;
  for (std::size_t k = 0; k < g.drawables.size(); ++k) {
    const Drawable& d = g.drawables[k];
    if (InFrustum(d.box, K, T_camera_world, g.near_m, g.far_m)) {
      order.emplace_back((R * d.box.center() + tr).squaredNorm(), static_cast<int>(k));
    }
  }
  std::sort(order.begin(), order.end());
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  for (const auto& [distance, k] : order) {
    const Drawable& d = g.drawables[static_cast<std::size_t>(k)];
    if (d.terrain >= 0 || d.mesh >= 0) {
      TerrainDrawable& t = d.terrain >= 0 ? g.terrain_drawables[static_cast<std::size_t>(d.terrain)]
                                          : g.mesh_drawables[static_cast<std::size_t>(d.mesh)];
      if (t.texture.tiled) {
        g.program->UseTiled(t.texture.tiling_seed, t.texture.tiling);
      } else {
        g.program->Use(SurfaceProgram::Kind::kFootprint);
      }
      const double error_px = g.appearance.object_far_error_px;
      g.DrawTerrain(
          t, center_xy,
          d.mesh < 0 ? nullptr : &MeshLevelAt(t.levels, d.box, center_xy, K.fx, error_px));
    } else {
      g.program->Use(d.flat     ? SurfaceProgram::Kind::kFootprint
                     : d.curved ? SurfaceProgram::Kind::kOutlineCore
                                : SurfaceProgram::Kind::kIsotropic);
      glCallList(g.ObjectList(d, K.fx, center_xy));
    }
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  if (track_marks_)
    track_marks_->Draw(T_world_camera.translation(), sun_world, g.appearance.ambient,
                       g.appearance.diffuse);
  if (g.leaf_crowns) g.leaf_crowns->Begin(view, sun_world, g.lit ? g.exposure : 1.0);
  if (g.leaf_crowns) g.leaf_crowns->Draw(LeafCrowns::Pass::kCore, order, g.drawables);
  g.program->Use(SurfaceProgram::Kind::kIsotropic);
  for (std::size_t k = 0; k < g.occluders.size(); ++k) {
    const sim::OccluderPose pose = sim::OccluderPoseAt(g.occluders[k], t_s);
    glPushMatrix();
    glTranslated(pose.position_m.x(), pose.position_m.y(),
                 g.terrain->Height(pose.position_m.x(), pose.position_m.y()));
    glRotated(units::Degrees(pose.yaw_rad), 0, 0, 1);
    glCallList(g.occluder_lists[k]);
    glPopMatrix();
  }
  if (g.sky) g.sky->Draw(view, sun_world, g.appearance.sky_gray, g.lit ? g.exposure : 1.0, K);
  g.DrawOutlineFringes(order);
  g.program->End();
  g.ReadBack(gray, depth);
}

}  // namespace trackbed::render
