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
// the neighbour's edge, and the neighbour's triangles along that edge are fanned
// to the same vertices (bit for bit), so chunks meet without cracks and without
// T-junctions, which a rasterizer need not fill.
//
// Blend: level k → k + 1 over distances [2^k, 1.5·2^k]·full_detail_m.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/sim/terrain.h"

namespace trackbed::render {

/// One drawn terrain vertex, as OpenGL's interleaved arrays take it.
struct TerrainVertex {
  float x, y, z;     // world [m]
  float nx, ny, nz;  // unit normal
  float s, t;        // texture coordinates [repeats]
};

/// A rectangle of a terrain's grid vertices, [i0, i1] × [j0, j1].
struct GridWindow {
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  bool operator==(const GridWindow& o) const {
    return i0 == o.i0 && j0 == o.j0 && i1 == o.i1 && j1 == o.j1;
  }
  /// The whole grid of `terrain`.
  static GridWindow Whole(const sim::Terrain& terrain) {
    return {0, 0, terrain.cols() - 1, terrain.rows() - 1};
  }
};

/// Levels of detail of a window of a Terrain's grid, and the meshes of its chunks.
class TerrainDetail {
 public:
  /// Coarsest level: every 8th grid vertex.
  static constexpr int kMaxLevel = 3;
  /// Most grid cells it meshes: it holds every level's heights and normals over
  /// its window.
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
    // What the triangles depend on: the level and the finer neighbours' levels.
    // Meshes of a chunk with the same topology have the same indices.
    int topology = -1;
    const Chunk* chunk = nullptr;  // the chunk it was built for
  };

  /// The grid's vertices in `window` (the whole grid by default), whose corners other
  /// than the grid's own must be multiples of `chunk_cells`; `full_detail_m` ≤ 0 draws
  /// the full grid everywhere. A vertex's levels do not depend on the window: heights
  /// beyond it are read from the terrain. Throws std::invalid_argument when
  /// `chunk_cells` is not a positive multiple of 2^kMaxLevel, the window is not one
  /// of the grid's, or it has more than kMaxCells cells.
  TerrainDetail(const sim::Terrain& terrain, double full_detail_m, int chunk_cells = 16,
                std::optional<GridWindow> window = std::nullopt);

  const GridWindow& window() const { return window_; }

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
  // Index of grid vertex (i, j) in the window's arrays.
  std::size_t Index(int i, int j) const {
    return static_cast<std::size_t>(j - window_.j0) * cols_ + (i - window_.i0);
  }
  // Vertices a finer neighbour puts along one side: `per_cell` between each two of
  // the mesh's, from vertex `first` on, in the order of growing i or j.
  struct SideVertices {
    std::uint32_t first = 0;
    int per_cell = 0;
  };
  TerrainVertex BlendedVertex(int i, int j, const Eigen::Vector2d& center_xy,
                              double meters_per_repeat) const;
  std::array<int, 4> SideLevels(const Chunk& c, const Eigen::Vector2d& center_xy) const;
  void PutSidesOnCoarserEdges(const Chunk& c, int level, const std::array<int, 4>& side_level,
                              Mesh* mesh) const;
  std::array<SideVertices, 4> AddFinerSideVertices(const Chunk& c, int level,
                                                   const std::array<int, 4>& side_level,
                                                   const Eigen::Vector2d& center_xy,
                                                   double meters_per_repeat, Mesh* mesh) const;
  void Triangulate(const Chunk& c, int level, const std::array<SideVertices, 4>& sides,
                   Mesh* mesh) const;
  void BuildLevels(const sim::Terrain& terrain);
  void BuildChunks(const sim::Terrain& terrain, int chunk_cells);
  void DistanceRange(const Chunk& c, const Eigen::Vector2d& p, double* d_min, double* d_max) const;

  const sim::Terrain& terrain_;
  double full_detail_m_;
  GridWindow window_;
  int cols_, rows_;  // vertices of the window
  // Per level: height and unit normal at every grid vertex.
  std::array<std::vector<float>, kMaxLevel + 1> z_;
  std::array<std::vector<Eigen::Vector3f>, kMaxLevel + 1> n_;
  std::vector<Chunk> chunks_;
};

}  // namespace trackbed::render
