// Simplified far versions of a mesh object's chunk (mesh_chunks.h), chosen per view by
// the rule of the far trees (object_detail.h; docs/rendering.md, "mesh objects"). Private
// to the renderer.
//
// Each coarser version is made from the full one by meshoptimizer's simplifier
// (meshopt_simplify: edge collapses onto existing vertices, ordered by a quadric error),
// aiming at a quarter of the previous version's triangles, with
// meshopt_SimplifyLockBorder: no vertex on the chunk's border (an edge of one triangle
// only: the cuts between chunks and the mesh's own open edges) moves or goes, so two
// neighbouring chunks drawn at different versions meet along the same edges, the full
// version's, and leave no crack. A version references the chunk's vertices: kept
// vertices keep their positions, normals and texture coordinates.
//
// A version's departure is meshoptimizer's own error of it, made absolute
// (result_error × meshopt_simplifyScale, the chunk's extent): the square root of the
// largest quadric error among its collapses, an area-weighted sum of the squared
// distances of the collapsed vertex from the planes of the full version's triangles
// merged into it. It is a measure of how far the surface moves, not a bound on it: the
// pixels are checked against the bound by rendering (tests/mesh_chunks_test.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "mesh_surfaces.h"

namespace trackbed::render {

/// One version of a chunk: a range of its index buffer.
struct MeshLevel {
  std::uint32_t first_index = 0;  ///< where its triangles start in the chunk's indices
  std::uint32_t index_count = 0;  ///< three per triangle
  double departure_m = 0.0;       ///< how far its surface departs from the full one's (above)
};

/// Versions stop when one keeps more than this share of the previous one's triangles.
inline constexpr double kMeshLevelMinReduction = 0.75;
/// At most this many versions besides the full one.
inline constexpr int kMeshMaxFarVersions = 4;

/// The full version of `s`: all its indices, departure 0.
std::vector<MeshLevel> MeshFullVersion(const MeshSurface& s);

/// The full version of `s`, then coarser versions made as above, their indices appended
/// to `s->indices`: each about a quarter of the previous one's triangles, departing
/// further, until one would keep more than kMeshLevelMinReduction of the previous one's,
/// or kMeshMaxFarVersions are made.
std::vector<MeshLevel> AddMeshFarVersions(MeshSurface* s);

/// The version to draw: the coarsest whose departure is under `max_error_px` at focal
/// length `focal_px`, seen from `detail_center_xy` at the distance in plan to the nearest
/// point of `box` (FarVersionDistance); the full one when max_error_px is 0.
const MeshLevel& MeshLevelAt(const std::vector<MeshLevel>& levels, const Eigen::AlignedBox3d& box,
                             const Eigen::Vector2d& detail_center_xy, double focal_px,
                             double max_error_px);

}  // namespace trackbed::render
