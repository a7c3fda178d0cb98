// The shader program every surface is drawn with. Private to the renderer.
//
// Light, per vertex as the fixed-function pipeline lights: ambient and the sun's
// diffuse term; with scene lighting (scene_lighting.h) the sun's term is shadowed and
// the whole scaled by the light map's gain, read per fragment at the fragment's world
// x, y, then by the exposure; with the robot's shadow (robot_shadow.h) the sun's term
// is also scaled per fragment by the share of the sun's disc the robot's boxes leave.
//
// Texture, per fragment, as a camera pixel sees it: the mean of the texture over the
// pixel's footprint, in one trilinear lookup. The footprint is the ellipse
// the pixel's sides map to in the texture (from the singular vectors of the texture
// coordinates' screen derivatives); the lookup reads the layer pre-filtered for its
// length over its width (the nearest power of two, up to 2^kMaxAnisotropyLog2) and
// the direction of its major axis (footprint_mips.h), at the mip level whose texel is
// the footprint's length over the layer's (the terrain, boxes, the ceiling). Cylinders,
// crowns and people are drawn by a second program that reads their texture (one
// layer) at the level llvmpipe takes from the quad's derivatives (about the
// footprint's length), trilinearly: a third of the footprint lookup's per-pixel cost.
//
// Outlines of cylinders and spheres (trunks, crowns): the core program leaves out the
// pixels whose centre lies less than half a pixel inside the outline of the true shape
// (from its centre and radius, an attribute per shape, not the facets); after every
// other draw the fringe program draws a band about each outline (two quads along an
// upright cylinder's silhouette lines, an annulus about a sphere's outline circle; the
// renderer's band lists), far to near, each pixel of it blended over what is behind by
// the fraction inside the outline (as for a straight edge), shaded where its ray meets
// the shape grown by a pixel and the facets' chords; then the depth program writes the
// depth of the true shape's point where the shape covers at least half the pixel, so
// that the depth image holds what most of each pixel shows.
//
// The driver's anisotropic filtering (GL_EXT_texture_filter_anisotropic) is not used:
// its sample pattern differs between Mesa versions. docs/rendering.md has what it gives
// against a supersampled render.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdint>

#include <Eigen/Core>

#include "trackbed/common/pinhole_camera.h"
#include "trackbed/render/procedural_texture.h"
#include "trackbed/render/robot_shadow.h"
#include "trackbed/render/scene_lighting.h"

namespace trackbed::render {

/// Segments of the annulus drawn about a sphere's outline (the fringe's band).
inline constexpr int kOutlineRingSegments = 24;

class SurfaceProgram {
 public:
  /// Compiles the program in the current context; with a light map (scene lighting),
  /// uploads it on texture unit 1; with `robot_shadow`, the sun's light shadowed by the
  /// robot's boxes (robot_shadow.h). Throws std::runtime_error when the driver cannot.
  SurfaceProgram(const LightMap* map, double ambient, double diffuse, bool robot_shadow = false);
  SurfaceProgram(const SurfaceProgram&) = delete;
  SurfaceProgram& operator=(const SurfaceProgram&) = delete;

  /// How a draw reads its texture: over the footprint from the layers (the ground's, a
  /// box's), or at the level llvmpipe takes from the quad's derivatives (a cylinder's, a
  /// crown's); a curved object's core and, in later passes, the band about its outline:
  /// its colour, then its depth.
  enum class Kind {
    kFootprint = 0,
    kIsotropic = 1,
    kOutlineCore = 2,
    kOutlineFringe = 3,
    kOutlineDepth = 4,
    kFootprintTiled = 5  ///< the footprint's, the ground tiled stochastically (ground_tiling.h)
  };

  /// Draws with the programs until End, the isotropic one first: `view` maps world to
  /// OpenGL eye coordinates, `sun` is the unit vector towards the sun in the world,
  /// `exposure` scales the output (1 without a light map), `K` the camera; `shadow` the
  /// robot's boxes in this frame (with robot_shadow; null: no box).
  void Begin(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun, double exposure,
             const geometry::PinholeCamera& K, const ShadowFrame* shadow = nullptr);
  /// Draws what follows with the program of `kind`.
  void Use(Kind kind);
  /// Draws what follows with the tiled footprint program, for a material of tiling seed
  /// `seed` and variation `v`.
  void UseTiled(std::uint32_t seed, const TileVariation& v);
  /// Back to no program.
  void End() const;

 private:
  struct Linked {
    GLuint program = 0;
    GLint world_from_eye = -1, sun_eye = -1, exposure = -1, outline_px_per_depth = -1,
          ray_from_window = -1, tile_seed = -1, tile_variation = -1, caster_from_eye = -1,
          caster_half = -1, caster_sun = -1, caster_count = -1;
  };
  static Linked Link(Kind kind, const LightMap* map, double ambient, double diffuse,
                     bool robot_shadow);

  Linked programs_[6];
  bool tiled_set_ = false;  // the tiled program's uniforms, as last set
  std::uint32_t tile_seed_ = 0;
  TileVariation tiling_;
  GLuint light_texture_ = 0;
  Kind current_ = Kind::kIsotropic;
};

}  // namespace trackbed::render
