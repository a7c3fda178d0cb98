// Terrain: heights, normals and materials, and agreement with Bullet's heightfield.
#include "trackbed/sim/terrain.h"

#include <random>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/sim/world.h"

namespace trackbed::sim {
namespace {

TerrainOptions Rough() {
  TerrainOptions o;
  o.extent_m = {-6, -4, 6, 4};
  o.cell_size_m = 0.1;
  o.roughness.undulation_amplitude_m = 0.3;
  o.roughness.undulation_wavelength_m = 5.0;
  o.roughness.bump_amplitude_m = 0.04;
  o.roughness.bump_wavelength_m = 0.7;
  o.roughness.slope_x = 0.05;
  return o;
}

TEST(TerrainTest, FlatTerrainIsTheZeroPlane) {
  const Terrain t(TerrainOptions{}, 7);
  EXPECT_EQ(t.Height(1.23, -2.5), 0.0);
  EXPECT_TRUE(t.Sample(0.3, 0.3).normal.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(t.MaterialAt(0, 0).name, "hard_floor");
}

TEST(TerrainTest, PlaneSlopeGivesHeightAndNormal) {
  TerrainOptions o;
  o.roughness.slope_x = 0.2;
  o.roughness.slope_y = -0.1;
  const Terrain t(o, 1);
  EXPECT_NEAR(t.Height(1.37, 2.11), 0.2 * 1.37 - 0.1 * 2.11, 1e-12);
  EXPECT_TRUE(t.Sample(1.37, 2.11).normal.isApprox(Eigen::Vector3d(-0.2, 0.1, 1).normalized()));
}

TEST(TerrainTest, SameSeedSameGroundOtherSeedOtherGround) {
  const Terrain a(Rough(), 3), b(Rough(), 3), c(Rough(), 4);
  EXPECT_EQ(a.Tile(0, 0)->heights, b.Tile(0, 0)->heights);
  EXPECT_NE(a.Tile(0, 0)->heights, c.Tile(0, 0)->heights);
  EXPECT_GT(a.Tile(0, 0)->max_height_m - a.Tile(0, 0)->min_height_m, 0.2);
  // Within the bounds the terrain gives for every height.
  EXPECT_GE(a.Tile(0, 0)->min_height_m, a.min_height_bound_m());
  EXPECT_LE(a.Tile(0, 0)->max_height_m, a.max_height_bound_m());
}

TEST(TerrainTest, AGrownWorldKeepsItsHeights) {
  // Heights are a function of the seed and the point alone: a world grown by
  // whole cells on every side has the same ground where the two overlap.
  const Terrain small(Rough(), 9);
  TerrainOptions grown = Rough();
  grown.extent_m = {-16, -9, 26, 14};
  const Terrain big(grown, 9);
  for (double x = -6.0; x <= 6.0; x += 0.37) {
    for (double y = -4.0; y <= 4.0; y += 0.41) {
      // The same point up to the rounding of its grid coordinates.
      ASSERT_NEAR(small.Height(x, y), big.Height(x, y), 1e-12) << x << ", " << y;
    }
  }
}

TEST(TerrainTest, NormalIsTheGradientOfTheHeight) {
  const Terrain t(Rough(), 5);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(-5.5, 5.5), uy(-3.5, 3.5);
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), y = uy(rng), h = 1e-6;
    const GroundSample s = t.Sample(x, y);
    // Central differences stay inside one triangle except on edges: skip those.
    const double dzdx = (t.Height(x + h, y) - t.Height(x - h, y)) / (2 * h);
    const double dzdy = (t.Height(x, y + h) - t.Height(x, y - h)) / (2 * h);
    const Eigen::Vector3d n = Eigen::Vector3d(-dzdx, -dzdy, 1).normalized();
    if ((n - s.normal).norm() > 1e-3) continue;  // a cell edge
    EXPECT_NEAR((n - s.normal).norm(), 0.0, 1e-6);
  }
}

TEST(TerrainTest, HeightMatchesBulletRayCastOnTheHeightfield) {
  World world(WorldOptions{}, Terrain(Rough(), 9), {});
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> ux(-5.9, 5.9), uy(-3.9, 3.9);
  for (int k = 0; k < 300; ++k) {
    const double x = ux(rng), y = uy(rng);
    const auto hit = world.CastRay({x, y, 5.0}, {x, y, -5.0}, kGroupTerrain);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->point_world.z(), world.terrain().Height(x, y), 1e-6) << x << " " << y;
  }
}

TEST(TerrainTest, LaterRegionsCoverEarlierOnes) {
  TerrainOptions o;
  o.default_material = "grass";
  MaterialRegion sand;
  sand.material = "dry_sand";
  sand.min_m = {-2, -2};
  sand.max_m = {2, 2};
  MaterialRegion clay;
  clay.material = "clay";
  clay.shape = MaterialRegion::Shape::kCircle;
  clay.center_m = {1.5, 1.5};
  clay.radius_m = 1.0;
  o.regions = {sand, clay};
  const Terrain t(o, 1);
  EXPECT_EQ(t.MaterialAt(-1, -1).name, "dry_sand");
  EXPECT_EQ(t.MaterialAt(1.6, 1.6).name, "clay");
  EXPECT_EQ(t.MaterialAt(4, 4).name, "grass");
}

TEST(TerrainTest, UnknownMaterialIsRejectedWithTheField) {
  TerrainOptions o;
  o.default_material = "moon_dust";
  try {
    Terrain t(o, 1);
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "default_material");
    EXPECT_NE(std::string(e.what()).find("unknown material 'moon_dust'"), std::string::npos);
  }
}

}  // namespace
}  // namespace trackbed::sim
