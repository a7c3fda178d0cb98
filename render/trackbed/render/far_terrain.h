// The far terrain of a large world: nested square rings of coarser and coarser
// grids around the window of the grid that TerrainDetail draws near the robot
// (a clipmap's rings, after Losasso & Hoppe 2004, "Geometry clipmaps").
//
// Ring k (k = TerrainDetail::kMaxLevel, … , kMaxLevel) is the surface through
// every 2^k-th grid vertex, split along the same diagonal as Terrain and Bullet
// split a cell, with the normals TerrainDetail gives level k: the first ring is
// exactly the near window's coarsest level, so the ground does not change where
// they meet or when the window moves. Each ring is `kRingQuads` of its quads wide
// around the one inside it. Where a ring meets the coarser one outside it, the
// finer ring's edge vertices between the coarser ring's lie on its edge, and the
// coarser ring's quads take them too: the two share every vertex of the seam, with
// no T-junction for the rasterizer to open a crack at. The first ring's inner edge
// hangs a skirt down, which hides the gaps to near chunks meshed finer than it
// (mixed materials, the blend within the window).
//
// A quad takes the material of the cell at its centre; a ring is cut into blocks
// of kBlockQuads × kBlockQuads quads, one piece per material in a block, for culling.
#pragma once

#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/render/terrain_detail.h"
#include "trackbed/sim/terrain.h"

namespace trackbed::render {

class FarTerrain {
 public:
  /// Coarsest ring: every 64th grid vertex.
  static constexpr int kMaxLevel = 6;
  /// Width of a ring in its own quads.
  static constexpr int kRingQuads = 16;
  /// Side of a culling block in quads.
  static constexpr int kBlockQuads = 8;

  /// One material of one block: its triangles, counter-clockwise from above.
  struct Piece {
    int material = 0;  ///< index into Terrain::materials()
    Eigen::AlignedBox3d box;
    std::vector<TerrainVertex> vertices;
    std::vector<std::uint32_t> indices;
  };

  /// Rings around `inner` (corners multiples of 2^kMaxLevel of TerrainDetail, or the
  /// grid's edges) until they reach `reach_m` beyond it on every side or the grid's
  /// edge; texture coordinates are world metres over `meters_per_repeat(material)`.
  FarTerrain(const sim::Terrain& terrain, const GridWindow& inner, double reach_m,
             const std::vector<double>& meters_per_repeat);

  const std::vector<Piece>& pieces() const { return pieces_; }
  /// The outermost ring's outer edge.
  const GridWindow& outer() const { return outer_; }

 private:
  struct RingLattice;  // a ring's lattice positions, heights and normals
  static RingLattice SampleRing(const sim::Terrain& terrain, const GridWindow& out, int s);
  static void StitchOuterEdges(const sim::Terrain& terrain, const GridWindow& out, int s,
                               RingLattice* r);
  Piece& PieceFor(int block_a, int block_b, int material);
  void AddVertex(Piece* p, double x, double y, double z, const Eigen::Vector3d& n,
                 double s_offset_m);
  void AddQuads(const sim::Terrain& terrain, const RingLattice& r, const GridWindow& in, int s,
                bool meet_finer);
  void AddSkirts(const sim::Terrain& terrain, const RingLattice& r, const GridWindow& in);

  GridWindow outer_;
  std::vector<double> meters_per_repeat_;
  std::vector<Piece> pieces_;
  int ring_ = 0;                                                       // the ring being built
  std::map<std::tuple<int, int, int, int>, std::size_t> piece_index_;  // ring, block, material
};

}  // namespace trackbed::render
