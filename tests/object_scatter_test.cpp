// Procedural scatter: objects a pure function of the seed and the lattice cell,
// at the asked density, clear of the kept-clear paths, on the listed materials.
#include "trackbed/sim/object_scatter.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"

namespace trackbed::sim {
namespace {

TerrainOptions Field() {
  TerrainOptions t;
  t.extent_m = {-50, -50, 50, 50};
  t.default_material = "grass";
  MaterialRegion sand;
  sand.material = "dry_sand";
  sand.min_m = {0, 0};
  sand.max_m = {50, 50};
  t.regions.push_back(sand);
  return t;
}

ObjectScatter Trees(double density) {
  ObjectScatter s;
  s.density_per_100m2 = density;
  return s;
}

TEST(ObjectScatterTest, AFunctionOfTheSeedAlone) {
  const auto a = ScatterObjects(Trees(2.0), 17, Field());
  const auto again = ScatterObjects(Trees(2.0), 17, Field());
  const auto other = ScatterObjects(Trees(2.0), 18, Field());
  ASSERT_EQ(a.size(), again.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].center_m, again[k].center_m);
    EXPECT_EQ(a[k].radius_m, again[k].radius_m);
    EXPECT_EQ(a[k].height_m, again[k].height_m);
  }
  EXPECT_NE(a.front().center_m, other.front().center_m);
}

TEST(ObjectScatterTest, OneObjectPerCellOfTheDensity) {
  // 2 per 100 m² over 100 m × 100 m: cells of √50 m, about 200 objects, each
  // within the ranges, two never closer than 0.4 of a cell.
  const auto trees = ScatterObjects(Trees(2.0), 5, Field());
  EXPECT_GT(trees.size(), 190u);
  EXPECT_LT(trees.size(), 215u);
  const double cell = 10.0 / std::sqrt(2.0);
  for (std::size_t a = 0; a < trees.size(); ++a) {
    EXPECT_EQ(trees[a].kind, "tree");
    EXPECT_EQ(trees[a].shape, StaticObject::Shape::kCylinder);
    EXPECT_EQ(trees[a].appearance, "bark");
    EXPECT_GE(trees[a].radius_m, 0.15);
    EXPECT_LE(trees[a].radius_m, 0.25);
    EXPECT_GE(trees[a].height_m, 3.0);
    EXPECT_LE(trees[a].height_m, 6.0);
    for (std::size_t b = a + 1; b < trees.size(); ++b) {
      ASSERT_GE((trees[a].center_m - trees[b].center_m).norm(), 0.4 * cell - 1e-9);
    }
  }
}

TEST(ObjectScatterTest, TilesScatteredApartGiveTheWhole) {
  // Two halves of a region, scattered separately, hold exactly the whole's objects:
  // a tile of a large world needs nothing but the seed.
  ObjectScatter whole = Trees(3.0), west = Trees(3.0), east = Trees(3.0);
  whole.region_m = {-40, -30, 40, 30};
  west.region_m = {-40, -30, 0, 30};
  east.region_m = {0, -30, 40, 30};
  const auto all = ScatterObjects(whole, 9, Field());
  auto parts = ScatterObjects(west, 9, Field());
  const auto e = ScatterObjects(east, 9, Field());
  parts.insert(parts.end(), e.begin(), e.end());
  ASSERT_EQ(all.size(), parts.size());
  for (const StaticObject& o : all) {
    const bool found = std::any_of(parts.begin(), parts.end(), [&](const StaticObject& p) {
      return p.center_m == o.center_m && p.radius_m == o.radius_m && p.height_m == o.height_m;
    });
    EXPECT_TRUE(found) << o.center_m.transpose();
  }
}

TEST(ObjectScatterTest, KeepsTheRouteClearAndStandsOnTheListedMaterial) {
  ObjectScatter s = Trees(5.0);
  s.materials = {"dry_sand"};
  s.clearance_m = 1.5;
  const std::vector<Eigen::Vector2d> route = {{5, 5}, {45, 20}, {10, 40}};
  s.keep_clear = {route};
  const auto trees = ScatterObjects(s, 3, Field(), {{Eigen::Vector2d(30, 30)}});
  ASSERT_GT(trees.size(), 50u);
  double nearest = 1e9;
  for (const StaticObject& o : trees) {
    EXPECT_EQ(Field().MaterialNameAt(o.center_m.x(), o.center_m.y()), "dry_sand");
    EXPECT_GE((o.center_m - Eigen::Vector2d(30, 30)).norm(), o.radius_m + 1.5);
    for (std::size_t k = 0; k + 1 < route.size(); ++k) {
      const Eigen::Vector2d a = route[k], ab = route[k + 1] - a;
      const double t = std::clamp((o.center_m - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double d = (o.center_m - (a + t * ab)).norm() - o.radius_m;
      EXPECT_GE(d, 1.5);
      nearest = std::min(nearest, d);
    }
  }
  EXPECT_LT(nearest, 3.0);  // kept clear, not kept away
}

TEST(ObjectScatterTest, BenchesAreBoxesWithAYaw) {
  ObjectScatter s = Trees(1.0);
  s.type = "bench";
  s.height_m = {0.45, 0.45};
  const auto benches = ScatterObjects(s, 4, Field());
  ASSERT_FALSE(benches.empty());
  EXPECT_EQ(benches[0].shape, StaticObject::Shape::kBox);
  EXPECT_EQ(benches[0].appearance, "wood");
  EXPECT_EQ(benches[0].size_m, Eigen::Vector3d(1.5, 0.5, 0.45));
  EXPECT_NE(benches[0].yaw_rad, benches[1].yaw_rad);
}

TEST(ObjectScatterTest, BadEntriesNameTheirKey) {
  const auto field_of = [](ObjectScatter s) {
    try {
      s.Validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return std::string("none");
  };
  ObjectScatter wall = Trees(1.0);
  wall.type = "wall";
  EXPECT_EQ(field_of(wall), "type");
  EXPECT_EQ(field_of(Trees(0.0)), "density_per_100m2");
  ObjectScatter radius = Trees(1.0);
  radius.radius_m = {0.3, 0.1};
  EXPECT_EQ(field_of(radius), "radius_m");
  ObjectScatter region = Trees(1.0);
  region.region_m = {5, 0, 1, 3};
  EXPECT_EQ(field_of(region), "region_m");
}

}  // namespace
}  // namespace trackbed::sim
