// Terrain: a heightfield with material regions.
//
// Heights live on a regular grid (x fastest), held in tiles generated when a
// query first needs them and dropped when far (trackbed/sim/terrain_tile.h), so
// a terrain's memory does not grow with its area. Between grid points the surface
// is the two-triangle split of each cell along the (i, j)–(i+1, j+1) diagonal,
// exactly as Bullet's btHeightfieldTerrainShape triangulates it with
// flipQuadEdges = true, so the track model, the physics and the renderer all
// see the same surface. Roughness is seeded value noise: long-wave undulation
// plus short-wave bumps plus a constant slope, each a lattice noise of the
// seed alone (trackbed/sim/lattice_noise.h).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/common/archive.h"
#include "trackbed/sim/elevation_grid.h"
#include "trackbed/sim/lattice_noise.h"
#include "trackbed/sim/soil_variation.h"
#include "trackbed/sim/terrain_material.h"
#include "trackbed/sim/terrain_tile.h"

namespace trackbed::sim {

/// Procedural roughness of the ground. All zero gives a flat floor at z = 0.
struct TerrainRoughness {
  /// Peak amplitude of long-wave hills [m], >= 0.
  double undulation_amplitude_m = 0.0;
  /// Wavelength of the hills [m], > 0.
  double undulation_wavelength_m = 8.0;
  /// Peak amplitude of short bumps [m], >= 0.
  double bump_amplitude_m = 0.0;
  /// Wavelength of the bumps [m], > 0.
  double bump_wavelength_m = 0.6;
  /// Constant slope dz/dx [-] (rise over run).
  double slope_x = 0.0;
  /// Constant slope dz/dy [-].
  double slope_y = 0.0;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("undulation_amplitude_m", &undulation_amplitude_m);
    a->Visit("undulation_wavelength_m", &undulation_wavelength_m);
    a->Visit("bump_amplitude_m", &bump_amplitude_m);
    a->Visit("bump_wavelength_m", &bump_wavelength_m);
    a->Visit("slope_x", &slope_x);
    a->Visit("slope_y", &slope_y);
  }
};

/// A digital elevation model under the terrain: its file (read by
/// assets/trackbed/assets/dem_reader.h) and the point of it that becomes the world's
/// origin. Its heights are the terrain's, less the height at that point, plus the
/// roughness above (which may add relief to a coarse model).
struct DemOptions {
  /// The raster file (GeoTIFF, ESRI ASCII grid, ...), relative to the scenario's
  /// folder; empty for none. Its coordinate system must be projected, in metres.
  std::string file;
  /// Easting and northing [m] in the file's coordinate system that become x = y = 0.
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();

  bool enabled() const { return !file.empty(); }
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("file", &file);
    a->Visit("origin", &origin_m);
  }
};

/// A Gazebo heightmap image under the terrain (docs/gazebo_users.md, read by
/// assets/trackbed/assets/heightmap_reader.h): a square greyscale image (8 or 16 bits
/// a pixel) whose pixels are the heights at size_m.x × size_m.y centred on pos_m, the
/// image seen from above (its top row at the highest y, its left column at the lowest
/// x, the corner pixels' centres at the corners); black at pos_m.z, the brightest
/// pixel size_m.z above it (Gazebo's scaling). The roughness is added on top.
struct HeightmapOptions {
  /// The image (PNG, ...), relative to the scenario's folder; absolute once loaded.
  std::string file;
  /// Span along x and y and the brightest pixel's height [m], each > 0.
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();
  /// The image's centre and its black level in the world [m].
  Eigen::Vector3d pos_m = Eigen::Vector3d::Zero();

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("file", &file);
    a->Visit("size_m", &size_m);
    a->Visit("pos_m", &pos_m);
  }
};

/// Where a material lies: an axis-aligned rectangle or a disc in the world's xy plane.
struct MaterialRegion {
  enum class Shape { kRectangle, kCircle };
  /// Name of a built-in or scenario-defined material.
  std::string material;
  Shape shape = Shape::kRectangle;
  /// Rectangle corners [m] (min and max x, y).
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m = Eigen::Vector2d::Zero();
  /// Disc centre [m] and radius [m].
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double radius_m = 0.0;

  bool Contains(double x, double y) const;
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("material", &material);
    a->VisitEnum("shape", &shape, {{"rectangle", Shape::kRectangle}, {"circle", Shape::kCircle}});
    // Only the shape's own keys: those of the other shape are unknown keys.
    if (shape == Shape::kRectangle) {
      a->Visit("min", &min_m);
      a->Visit("max", &max_m);
    } else {
      a->Visit("center", &center_m);
      a->Visit("radius_m", &radius_m);
    }
  }
};

/// Everything that defines a terrain. Regions later in the list cover earlier ones.
struct TerrainOptions {
  /// World-frame extent [m]: x_min, y_min, x_max, y_max.
  Eigen::Vector4d extent_m{-5.0, -5.0, 5.0, 5.0};
  /// Grid spacing of the heightfield [m], > 0.
  double cell_size_m = 0.1;
  TerrainRoughness roughness;
  /// Material everywhere no region covers.
  std::string default_material = "hard_floor";
  /// Materials defined by the scenario in addition to the built-in ones.
  std::vector<TerrainMaterial> materials;
  std::vector<MaterialRegion> regions;
  /// Seeded point-to-point variation of the soil parameters (off by default).
  SoilVariationOptions soil_variation;
  /// A digital elevation model for the heights (off by default).
  DemOptions dem;
  /// A Gazebo heightmap image for the heights (absent by default; excludes `dem`).
  std::optional<HeightmapOptions> heightmap;

  /// Longest side a terrain may have [m]; it must also lie within this of the origin.
  static constexpr double kMaxSideM = 10000.0;

  void Validate() const;
  /// Grid cells over the extent (about).
  double cells() const;
  /// The box the terrain's grid points span [m] (x_min, y_min, x_max, y_max): the
  /// extent, its far sides moved out to the next whole cell.
  Eigen::Vector4d grid_extent_m() const;
  /// Index of the region that covers (x, y): the last one containing it; -1 for none.
  int RegionAt(double x, double y) const;
  /// Name of the material at (x, y): RegionAt's, else the default (Terrain gives a
  /// cell the material at its centre).
  const std::string& MaterialNameAt(double x, double y) const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("extent_m", &extent_m);
    a->Visit("cell_size_m", &cell_size_m);
    a->Visit("roughness", &roughness);
    a->Visit("default_material", &default_material);
    a->Visit("materials", &materials);
    a->Visit("regions", &regions);
    a->Visit("soil_variation", &soil_variation);
    a->Visit("dem", &dem);
    a->Visit("heightmap", &heightmap, archive::kOmitEmpty);
  }
};

/// Height, normal and material of the ground at one point.
struct GroundSample {
  double height_m = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  const TerrainMaterial* material = nullptr;
};

/// A heightfield terrain, immutable to its users. Queries outside the extent
/// clamp to the edge. Queries generate and drop tiles: call them from one thread
/// at a time.
class Terrain {
 public:
  /// Tiles a terrain holds at most (each at most 513 × 513 heights, 2.4 MB).
  static constexpr std::size_t kResidentTiles = 16;

  /// Checks the options and the materials; tiles are generated when first queried.
  /// `seed` drives the roughness noise; `base`, the elevation model read for
  /// options.dem (null without one), gives the heights under the roughness and must
  /// cover the extent. Throws OptionError on bad options.
  Terrain(const TerrainOptions& options, std::uint64_t seed,
          std::shared_ptr<const ElevationGrid> base = nullptr);

  /// Height of the surface at (x, y) [m], on the triangulated surface.
  double Height(double x, double y) const;
  /// Height(x, y) to the bit, computed from the seed without generating or holding a
  /// tile: for one-off queries scattered over a large world (placing objects).
  double HeightFromSeed(double x, double y) const;
  /// Height, upward unit normal and material at (x, y).
  GroundSample Sample(double x, double y) const;
  /// Material at (x, y) (of the grid cell containing the point).
  const TerrainMaterial& MaterialAt(double x, double y) const;
  /// Mechanical soil parameters at (x, y): `material`'s (the one Sample returned
  /// there), scaled by the soil variation fields.
  SoilPoint SoilAt(const TerrainMaterial& material, double x, double y) const;

  /// Height of grid vertex (i, j) [m], computed from the seed (what its tile holds).
  double VertexHeight(int i, int j) const;
  /// VertexHeight(i, j), read from its tile (generated if not held): for many
  /// vertices near each other.
  double GridHeight(int i, int j) const;
  /// Material index (into materials()) of grid cell (i, j), computed from the
  /// regions at the cell's centre (what its tile holds).
  std::uint8_t CellMaterial(int i, int j) const;
  /// Tile (ti, tj), generated if not held.
  std::shared_ptr<const TerrainTile> Tile(int ti, int tj) const;

  int cols() const { return cols_; }                            ///< Grid points along x.
  int rows() const { return rows_; }                            ///< Grid points along y.
  int tiles_x() const { return (cols_ - 2) / kTileCells + 1; }  ///< Tiles along x.
  int tiles_y() const { return (rows_ - 2) / kTileCells + 1; }  ///< Tiles along y.
  double cell_size_m() const { return cell_; }
  double x_min() const { return x0_; }
  double y_min() const { return y0_; }
  double x_max() const { return x0_ + cell_ * (cols_ - 1); }
  double y_max() const { return y0_ + cell_ * (rows_ - 1); }
  /// Bounds no height can leave [m]: the slope's plane over the extent and the
  /// elevation model's range, less and plus the roughness amplitudes (not the
  /// heights reached).
  double min_height_bound_m() const { return min_bound_; }
  double max_height_bound_m() const { return max_bound_; }
  /// All materials the terrain uses or defines (built-ins first).
  const std::vector<TerrainMaterial>& materials() const { return materials_; }
  /// The tiles held now and generated so far.
  const TerrainTileCache& tile_cache() const { return tiles_; }

 private:
  // The triangle under (x, y): its cell (i, j), the point's place in the cell
  // (u, v in [0, 1]), the cell corner's height, the triangle's rise per cell
  // along x and y, and the tile holding the cell.
  struct Facet {
    int i, j;
    double u, v, h00, dzdu, dzdv;
    const TerrainTile* tile;
  };
  Facet FacetAt(double x, double y) const;
  // The cell under (x, y) and the point's place in it.
  Facet CellAt(double x, double y) const;
  // Fills the facet's heights from the corners h00, h10, h01, h11.
  static void SetSlopes(double h00, double h10, double h01, double h11, Facet* f);
  // The tile holding grid cell (i, j).
  const TerrainTile& TileOfCell(int i, int j) const;
  TerrainTile GenerateTile(int ti, int tj) const;
  void ResolveMaterials(const TerrainOptions& options);

  TerrainOptions options_;
  double x0_, y0_, cell_;
  int cols_, rows_;
  double min_bound_ = 0.0, max_bound_ = 0.0;
  // The heights' four octaves: undulation and half its wavelength, bumps and half theirs.
  LatticeNoise hills_, hills2_, bumps_, bumps2_;
  std::shared_ptr<const ElevationGrid> base_;  // the elevation model, or null
  std::vector<TerrainMaterial> materials_;
  std::vector<SoilPoint> soils_;  // SoilOf(materials_[k])
  std::uint8_t default_material_ = 0;
  std::vector<std::uint8_t> region_material_;  // material index of each region
  SoilVariation soil_variation_;
  mutable TerrainTileCache tiles_{kResidentTiles};
  // The tile the last query used: a track's contact points stay in one for long.
  mutable std::shared_ptr<const TerrainTile> last_tile_;
};

}  // namespace trackbed::sim
