// A mesh object's large parts split into chunks, each culled against the view on its
// own bounds. Private to the renderer (docs/rendering.md, "mesh objects").
//
// A part of more than kMeshChunkTriangles triangles is split in two at the median of
// its triangles' centroids along the longest side of their bounds, and each half again
// until every piece holds at most that many: chunks of half to all of it, compact in
// space. The order is total (the centroid's coordinate, then the triangle's index), so
// the split does not depend on the sort's implementation; within a chunk the triangles
// keep the part's order. Each chunk has its own copy of the vertices its triangles use,
// with the part's positions, normals and texture coordinates unchanged: at full detail
// the chunks draw the part's triangles from the same vertices.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh_far_versions.h"
#include "mesh_surfaces.h"

namespace trackbed::render {

/// Parts with more triangles than this are split into chunks of at most this many.
/// About 0.2 ms of llvmpipe's time at 35 ns a triangle (docs/results/2026-12-07-mesh-cost.md):
/// a few hundred chunks for a million triangles, each culled for a box test.
inline constexpr std::size_t kMeshChunkTriangles = 8192;

/// `s` split as above into chunks of at most `max_triangles` (≥ 1) triangles; `s` itself
/// when it has no more. Every triangle of `s` is in exactly one chunk.
std::vector<MeshSurface> SplitMeshSurface(const MeshSurface& s, std::size_t max_triangles);

/// A chunk and its versions, the full one first (mesh_far_versions.h).
struct MeshChunk : MeshSurface {
  std::vector<MeshLevel> levels;
};

/// The parts of `m` (MeshSurfaces) split into chunks of at most kMeshChunkTriangles
/// triangles, each with its far versions (`far_versions`) or its full version only.
std::vector<MeshChunk> MeshChunks(const sim::MeshObject& m, bool far_versions);

}  // namespace trackbed::render
