// Terrain tiles: continuous across their seams (heights, normals, Bullet's
// triangulation), the same bits when dropped and generated again, and memory
// bounded by the tiles held, not the world's area.
#include "trackbed/sim/terrain_tile.h"

#include <random>

#include <gtest/gtest.h>

#include "trackbed/sim/terrain.h"
#include "trackbed/sim/world.h"

namespace trackbed::sim {
namespace {

// Rough ground over several tiles: 0.1 m cells, tiles of 51.2 m.
TerrainOptions Rough(double size_x_m, double size_y_m) {
  TerrainOptions o;
  o.extent_m = {-20, -10, -20 + size_x_m, -10 + size_y_m};
  o.cell_size_m = 0.1;
  o.roughness.undulation_amplitude_m = 0.3;
  o.roughness.undulation_wavelength_m = 5.0;
  o.roughness.bump_amplitude_m = 0.04;
  o.roughness.bump_wavelength_m = 0.7;
  o.roughness.slope_y = 0.03;
  MaterialRegion sand;
  sand.material = "dry_sand";
  sand.min_m = {25, 0};
  sand.max_m = {40, 20};
  o.regions = {sand};
  return o;
}

// The x of the seam between tiles 0 and 1.
double SeamX(const Terrain& t) { return t.x_min() + kTileCells * t.cell_size_m(); }

TEST(TerrainTileTest, NeighboursShareTheirEdgeVerticesBitForBit) {
  const Terrain t(Rough(80, 60), 4);
  ASSERT_EQ(t.tiles_x(), 2);
  ASSERT_EQ(t.tiles_y(), 2);
  const auto a = t.Tile(0, 0), b = t.Tile(1, 0), c = t.Tile(0, 1);
  EXPECT_EQ(a->cols, kTileCells + 1);
  EXPECT_EQ(b->i0, kTileCells);
  EXPECT_EQ(b->cols, t.cols() - kTileCells);
  EXPECT_EQ(c->rows, t.rows() - kTileCells);
  for (int j = 0; j < a->rows; ++j) {
    ASSERT_EQ(a->Height(kTileCells, j), b->Height(kTileCells, j)) << j;
    ASSERT_EQ(a->Height(kTileCells, j), t.VertexHeight(kTileCells, j)) << j;
  }
  for (int i = 0; i < a->cols; ++i) ASSERT_EQ(a->Height(i, kTileCells), c->Height(i, kTileCells));
}

TEST(TerrainTileTest, HeightsAndNormalsAreContinuousAcrossASeam) {
  const Terrain t(Rough(80, 60), 4);
  const double seam = SeamX(t);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uy(-9.9, 49.9);
  for (int k = 0; k < 200; ++k) {
    const double y = uy(rng), e = 1e-7;
    ASSERT_NEAR(t.Height(seam - e, y), t.Height(seam + e, y), 1e-6) << y;
    // The normals on either side belong to the two triangles that share the seam's
    // edge: both contain the edge's direction (0, cell, dz).
    const GroundSample left = t.Sample(seam - e, y), right = t.Sample(seam + e, y);
    const double c = t.cell_size_m();
    const double j = std::floor((y - t.y_min()) / c);
    const Eigen::Vector3d edge(0, c,
                               t.VertexHeight(kTileCells, static_cast<int>(j) + 1) -
                                   t.VertexHeight(kTileCells, static_cast<int>(j)));
    EXPECT_NEAR(left.normal.dot(edge), 0.0, 1e-9) << y;
    EXPECT_NEAR(right.normal.dot(edge), 0.0, 1e-9) << y;
  }
}

TEST(TerrainTileTest, BulletAgreesOnEitherSideOfASeam) {
  World world(WorldOptions{}, Terrain(Rough(80, 60), 4), {});
  EXPECT_EQ(world.ground_tiles(), 4u);  // a small world's tiles are all in Bullet
  const double seam = SeamX(world.terrain());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ux(seam - 0.35, seam + 0.35), uy(-9.9, 49.9);
  for (int k = 0; k < 300; ++k) {
    const double x = k % 3 == 0 ? seam : ux(rng), y = uy(rng);  // a third exactly on it
    const auto hit = world.CastRay({x, y, 5.0}, {x, y, -5.0}, kGroupTerrain);
    ASSERT_TRUE(hit.has_value()) << x << " " << y;
    EXPECT_NEAR(hit->point_world.z(), world.terrain().Height(x, y), 1e-6) << x << " " << y;
  }
}

TEST(TerrainTileTest, ADroppedTileComesBackWithTheSameBits) {
  const Terrain t(Rough(300, 300), 8);  // 6 x 6 tiles
  ASSERT_EQ(t.tiles_x() * t.tiles_y(), 36);
  const auto first = t.Tile(1, 0);
  for (int tj = 0; tj < t.tiles_y(); ++tj) {
    for (int ti = 0; ti < t.tiles_x(); ++ti) t.Tile(ti, tj);
  }
  EXPECT_EQ(t.tile_cache().resident(), Terrain::kResidentTiles);
  const std::uint64_t generated = t.tile_cache().generated();
  const auto again = t.Tile(1, 0);  // dropped on the walk: generated again
  EXPECT_EQ(t.tile_cache().generated(), generated + 1);
  ASSERT_NE(first.get(), again.get());
  EXPECT_EQ(first->heights, again->heights);
  EXPECT_EQ(first->cell_material, again->cell_material);
  EXPECT_EQ(first->min_height_m, again->min_height_m);
  EXPECT_EQ(first->max_height_m, again->max_height_m);
}

TEST(TerrainTileTest, QueriesAcrossALargeWorldHoldABoundedNumberOfTiles) {
  // 1 km x 1 km at 0.1 m: 100 million cells, 400 tiles; nothing generated up front.
  World world(WorldOptions{}, Terrain(Rough(1000, 1000), 2), {});
  const Terrain& t = world.terrain();
  EXPECT_EQ(t.tiles_x() * t.tiles_y(), 400);
  EXPECT_EQ(t.tile_cache().generated(), 0u);
  EXPECT_EQ(world.ground_tiles(), 0u);
  // A drive across the world, sampling the ground and casting a ray down every 2 m
  // (at s = 512 m exactly through a tile's corner).
  for (double s = 0.0; s <= 1000.0; s += 2.0) {
    const double x = -20 + s, y = -10 + 0.7 * s;
    const GroundSample g = t.Sample(x, y);
    const auto hit = world.CastRay({x, y, g.height_m + 2}, {x, y, g.height_m - 2}, kGroupTerrain);
    ASSERT_TRUE(hit.has_value()) << s;
    ASSERT_NEAR(hit->point_world.z(), g.height_m, 1e-6) << s;
  }
  EXPECT_LE(t.tile_cache().resident(), Terrain::kResidentTiles);
  EXPECT_LE(world.ground_tiles(), World::kGroundTiles);
}

TEST(TerrainTileTest, HeightsFromTheSeedAndFromTilesAreTheSameBits) {
  const Terrain t(Rough(150, 150), 6);  // 3 x 3 tiles
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> ux(-20, 130), uy(-10, 140);
  std::uniform_int_distribution<int> ui(0, t.cols() - 1), uj(0, t.rows() - 1);
  for (int k = 0; k < 500; ++k) {
    const double x = ux(rng), y = uy(rng);
    ASSERT_EQ(t.HeightFromSeed(x, y), t.Height(x, y)) << x << ", " << y;
    const int i = ui(rng), j = uj(rng);
    ASSERT_EQ(t.GridHeight(i, j), t.VertexHeight(i, j)) << i << ", " << j;
  }
}

TEST(TerrainTileTest, TheCacheDropsTheLeastRecentlyFetched) {
  TerrainTileCache cache(2);
  int made = 0;
  const TerrainTileCache::Generate make = [&](int ti, int tj) {
    ++made;
    TerrainTile t;
    t.ti = ti;
    t.tj = tj;
    return t;
  };
  cache.Get(0, 0, make);
  cache.Get(1, 0, make);
  cache.Get(0, 0, make);  // (1, 0) is now the least recently fetched
  cache.Get(2, 0, make);
  EXPECT_EQ(made, 3);
  cache.Get(0, 0, make);  // still held
  EXPECT_EQ(made, 3);
  cache.Get(1, 0, make);  // dropped: made again
  EXPECT_EQ(made, 4);
  EXPECT_EQ(cache.resident(), 2u);
  EXPECT_EQ(cache.generated(), 4u);
  EXPECT_THROW(TerrainTileCache(0), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::sim
