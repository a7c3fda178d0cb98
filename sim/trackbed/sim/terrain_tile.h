// Terrain tiles: the ground's grid in squares, generated from the scene's seed
// when first needed and dropped, least recently used first, when more than a
// set number are held — so the memory a terrain holds is bounded by what is
// queried near the robot, not by the world's area.
//
// Tile (ti, tj) holds the grid vertices [ti·kTileCells, (ti+1)·kTileCells] ×
// [tj·kTileCells, (tj+1)·kTileCells], clipped to the grid: neighbouring tiles
// share their edge vertices, and every grid cell (i, j) lies in tile
// (i / kTileCells, j / kTileCells) with its four corners. A vertex's height is a
// function of the seed and the vertex alone (trackbed/sim/terrain.h), so a tile
// dropped and generated again holds the same bits.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace trackbed::sim {

/// Grid cells along a side of a terrain tile.
inline constexpr int kTileCells = 512;

/// One square of the terrain's grid.
struct TerrainTile {
  int ti = 0, tj = 0;  ///< Tile index.
  int i0 = 0, j0 = 0;  ///< Grid index of its first vertex.
  int cols = 0;        ///< Grid vertices along x.
  int rows = 0;        ///< Grid vertices along y.
  double min_height_m = 0.0, max_height_m = 0.0;
  std::vector<double> heights;              ///< Row-major, cols × rows.
  std::vector<std::uint8_t> cell_material;  ///< Row-major, (cols − 1) × (rows − 1).

  /// Height of grid vertex (i, j) (grid, not tile, indices).
  double Height(int i, int j) const {
    return heights[static_cast<std::size_t>(j - j0) * cols + (i - i0)];
  }
  /// Material index of grid cell (i, j).
  std::uint8_t CellMaterial(int i, int j) const {
    return cell_material[static_cast<std::size_t>(j - j0) * (cols - 1) + (i - i0)];
  }
};

/// The tiles a terrain holds, at most `capacity` of them.
class TerrainTileCache {
 public:
  using Generate = std::function<TerrainTile(int ti, int tj)>;

  /// At most `capacity` ≥ 1 tiles are held.
  explicit TerrainTileCache(std::size_t capacity);

  /// Tile (ti, tj), made by `generate` when not held; beyond the capacity the
  /// least recently fetched one is dropped (a caller's shared pointer keeps it
  /// alive). Every call for one cache must pass the same generator.
  const std::shared_ptr<const TerrainTile>& Get(int ti, int tj, const Generate& generate);

  std::size_t capacity() const { return capacity_; }
  /// Tiles held now.
  std::size_t resident() const { return tiles_.size(); }
  /// Tiles generated so far (a dropped tile fetched again counts again).
  std::uint64_t generated() const { return generated_; }

 private:
  struct Entry {
    std::shared_ptr<const TerrainTile> tile;
    std::uint64_t used = 0;
  };
  std::size_t capacity_;
  std::map<std::pair<int, int>, Entry> tiles_;
  std::uint64_t clock_ = 0, generated_ = 0;
};

}  // namespace trackbed::sim
