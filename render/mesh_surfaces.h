// Mesh objects (sim::MeshObject, users' files) as the renderer draws them. Private to
// the renderer.
//
// Each part (the triangles of one material) becomes one drawable: its vertices in the
// world frame (scaled, then placed by the object's pose), a unit normal per vertex and
// the file's texture coordinates; its texture is the material's base colour as a grey
// albedo. Normals come from the triangles: at each corner, the area-weighted mean of
// the normals of the triangles that share the corner's position (across texture seams)
// and lie within kCreaseDeg of the corner's own triangle, so that smooth surfaces are
// shaded smooth and edges sharper than that stay sharp. The file's own normals are not
// read.
//
// Grey albedo: each texel's red, green and blue decoded from sRGB (IEC 61966-2-1) to
// linear, multiplied by the base colour's (linear) and weighted by Rec. 709's luma
// coefficients (0.2126, 0.7152, 0.0722: the relative luminance of sRGB's primaries);
// the image resampled to a square of a power of two texels (the next at or above its
// larger side, in [16, 2048]) on a grey level of 0–255 a texel. A part without an image
// gets a uniform texture of its base colour's luminance.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/render/procedural_texture.h"
#include "trackbed/render/terrain_detail.h"
#include "trackbed/sim/world.h"

namespace trackbed::render {

/// Edges between triangles whose normals differ by more than this stay sharp [deg].
inline constexpr double kCreaseDeg = 60.0;

/// One part of a mesh object, ready for buffer objects.
struct MeshSurface {
  std::vector<TerrainVertex> vertices;  ///< World frame; texture coordinates the file's UVs.
  std::vector<std::uint32_t> indices;   ///< Triangles, counter-clockwise from outside.
  Eigen::AlignedBox3d box;              ///< The vertices' world bounds.
  /// Names the texture: parts of the same image and base colour share one.
  std::string texture_key;
  const sim::MeshPart* part = nullptr;  ///< The part (owned by the mesh object).
};

/// The parts of `m` (its visual mesh) placed in the world; parts without a triangle are
/// left out.
std::vector<MeshSurface> MeshSurfaces(const sim::MeshObject& m);

/// The grey albedo texture of `part` (see above). meters_per_repeat is 1: the texture
/// coordinates are the file's, one repeat per image.
Texture MeshPartTexture(const sim::MeshPart& part);

/// An sRGB-encoded byte decoded to linear light in [0, 1] (IEC 61966-2-1).
double SrgbToLinear(std::uint8_t encoded);

}  // namespace trackbed::render
