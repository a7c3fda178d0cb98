// Distance-dependent detail of the rendered terrain, without popping and the
// same for both cameras of a stereo pair.
//
// Far terrain drawn from the full 0.1 m grid is mostly sub-pixel triangles,
// and triangles, not pixels, bound llvmpipe's speed. Level k of the terrain is
// the surface through every 2^k-th grid vertex, split along the same diagonal
// as Terrain and Bullet split a cell. The drawn surface is a blend of levels
// whose weight is a continuous function of each vertex's horizontal distance
// from one point (the stereo rig's centre), so
//   * both cameras of a pair see the same ground;
//   * as the robot moves, the ground blends from one level to the next a
//     little each frame (under 0.5 mm per frame at 0.4 m/s) instead of
//     switching (the popping that made visual odometry worse when chunks
//     switched detail, docs/rendering.md);
//   * within `full_detail_m` the drawn surface is exactly the physical one.
// A chunk is meshed at the coarsest level all its vertices are fully blended
// to. Along a side it shares with a coarser neighbour, its vertices are put on
// the neighbour's edge, so chunks meet without cracks.
//
// Blend: level k → k + 1 over distances [2^k, 1.5·2^k]·full_detail_m.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/sim/terrain.h"

namespace trackbed::sim {

/// One drawn terrain vertex, as OpenGL's interleaved arrays take it.
struct TerrainVertex {
  float x, y, z;     // world [m]
  float nx, ny, nz;  // unit normal
  float s, t;        // texture coordinates [repeats]
};

/// Levels of detail of a Terrain's grid, and the meshes of its chunks.
class TerrainDetail {
 public:
  /// Coarsest level: every 8th grid vertex.
  static constexpr int kMaxLevel = 3;
  /// Most grid cells it meshes: it holds every level's heights and normals over
  /// the whole grid.
  static constexpr double kMaxCells = 16e6;

  /// A square of `chunk_cells` cells (fewer at the far edges) of one material.
  struct Chunk {
    int i0, j0, i1, j1;  // grid vertex range [i0, i1] × [j0, j1]
    int material;        // index into Terrain::materials()
    int max_level;       // coarsest level it can be meshed at (0 when it has several materials)
    Eigen::AlignedBox3d box;  // world bounds of every blend of its levels
    // The chunk across each side (one of them where it has several materials):
    // i = i0, i = i1, j = j0, j = j1; -1 at the terrain's edge.
    std::array<int, 4> neighbor{-1, -1, -1, -1};
  };

  /// The triangles of one chunk as seen from one centre.
  struct Mesh {
    std::vector<TerrainVertex> vertices;
    std::vector<std::uint32_t> indices;  // triangles, counter-clockwise from above
    int level = -1;                      // mesh level
    const Chunk* chunk = nullptr;        // the chunk it was built for
  };

  /// `full_detail_m` ≤ 0 draws the full grid everywhere. Throws
  /// std::invalid_argument when `chunk_cells` is not a positive multiple of 2^kMaxLevel
  /// or the grid has more than kMaxCells cells.
  TerrainDetail(const Terrain& terrain, double full_detail_m, int chunk_cells = 16);

  const std::vector<Chunk>& chunks() const { return chunks_; }
  double full_detail_m() const { return full_detail_m_; }

  /// Blend level at horizontal distance `distance_m` from the centre, in [0, kMaxLevel].
  double LevelAt(double distance_m) const;
  /// Level chunk `c` is meshed at when seen from `center_xy` (world, m).
  int MeshLevel(const Chunk& c, const Eigen::Vector2d& center_xy) const;
  /// True when chunk `c`'s mesh built from centre `a_xy` holds from `b_xy`: its
  /// blend is the same whole level over it from both, and so are its
  /// neighbours' mesh levels.
  bool SameMesh(const Chunk& c, const Eigen::Vector2d& a_xy, const Eigen::Vector2d& b_xy) const;
  /// Height of grid vertex (i, j) at blend level `level` [m].
  double Height(int i, int j, double level) const;
  /// Builds chunk `c`'s mesh seen from `center_xy`; texture coordinates are
  /// world metres over `meters_per_repeat`. Reuses `mesh`'s storage.
  void BuildMesh(const Chunk& c, const Eigen::Vector2d& center_xy, double meters_per_repeat,
                 Mesh* mesh) const;

 private:
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(j) * cols_ + i; }
  void DistanceRange(const Chunk& c, const Eigen::Vector2d& p, double* d_min, double* d_max) const;

  const Terrain& terrain_;
  double full_detail_m_;
  int cols_, rows_;
  // Per level: height and unit normal at every grid vertex.
  std::array<std::vector<float>, kMaxLevel + 1> z_;
  std::array<std::vector<Eigen::Vector3f>, kMaxLevel + 1> n_;
  std::vector<Chunk> chunks_;
};

}  // namespace trackbed::sim
