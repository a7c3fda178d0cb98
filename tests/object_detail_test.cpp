// Far versions of trees: how far their outlines can depart from the full version's,
// checked against the outlines of the spheres and cylinders as the renderer draws
// them, and the distances that gives.
#include "trackbed/render/object_detail.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

namespace trackbed::render {
namespace {

// The vertices of a unit sphere as the renderer's DrawSphere places them: rings every
// π/stacks of latitude from pole to pole, every 2π/slices of longitude.
std::vector<Eigen::Vector3d> SphereVertices(int slices, int stacks) {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i <= stacks; ++i) {
    const double a = M_PI * (-0.5 + static_cast<double>(i) / stacks);
    for (int k = 0; k < slices; ++k) {
      const double b = 2 * M_PI * k / slices;
      v.emplace_back(std::cos(a) * std::cos(b), std::cos(a) * std::sin(b), std::sin(a));
    }
  }
  return v;
}

// Where a convex shape's outline lies in the direction `u` of the image plane (seen
// along any direction perpendicular to it): its support function, max over vertices.
double Support(const std::vector<Eigen::Vector3d>& vertices, const Eigen::Vector3d& u) {
  double h = -1e300;
  for (const Eigen::Vector3d& v : vertices) h = std::max(h, v.dot(u));
  return h;
}

TEST(ObjectDetailTest, SagsAreHowFarTheFlattestFacetLiesInside) {
  EXPECT_NEAR(InscribedPolygonSag(1.0, 4), 1.0 - std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(InscribedPolygonSag(2.0, 6), 2.0 * (1.0 - std::sqrt(3.0) / 2.0), 1e-15);
  EXPECT_NEAR(SphereSag(1.0, 8, 5), 1.0 - std::cos(M_PI / 8) * std::cos(M_PI / 10), 1e-15);
  EXPECT_EQ(TreeLevelDeparture(2.0, 0.3, kTreeLevels[0]), 0.0);
  EXPECT_EQ(TreeLevelDeparture(2.0, 0.3, kTreeLevels[1]), SphereSag(2.0, 12, 8));
  // Without a crown, the trunk alone.
  EXPECT_EQ(TreeLevelDeparture(0.0, 0.3, kTreeLevels[2]), InscribedPolygonSag(0.3, 8));
}

// The full crown's outline and a coarser one's, in every direction of a grid: never
// farther apart than the coarser level's sag, and the worst seen within a quarter of
// it (the bound is not loose).
TEST(ObjectDetailTest, ACoarserCrownsOutlineStaysWithinItsSagOfTheFullOne) {
  const TreeTessellation& full = kTreeLevels[0];
  const std::vector<Eigen::Vector3d> f = SphereVertices(full.crown_slices, full.crown_stacks);
  for (std::size_t l = 1; l < kTreeLevels.size(); ++l) {
    const TreeTessellation& level = kTreeLevels[l];
    const std::vector<Eigen::Vector3d> c = SphereVertices(level.crown_slices, level.crown_stacks);
    double worst = 0.0;
    for (int e = 0; e <= 60; ++e) {
      const double elevation = M_PI * (-0.5 + e / 60.0);
      for (int a = 0; a < 240; ++a) {
        const double azimuth = 2 * M_PI * a / 240;
        const Eigen::Vector3d u(std::cos(elevation) * std::cos(azimuth),
                                std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
        worst = std::max(worst, std::abs(Support(f, u) - Support(c, u)));
      }
    }
    const double bound = TreeLevelDeparture(1.0, 0.0, level);
    EXPECT_LE(worst, bound + 1e-12) << "level " << l;
    EXPECT_GE(worst, 0.75 * bound) << "level " << l;
  }
}

TEST(ObjectDetailTest, TheParksTreesCoarsenOnlyFarAway) {
  // f = 381 px, half a pixel. A 7 m tree (crown radius 7/3 m, trunk 0.35 m): 12 x 8
  // facets from 94 m, 8 x 5 from 215 m, beyond the 120 m far plane; a 3 m tree (crown
  // 1 m): from 40 m and 92 m.
  const auto distance = [](double crown, double trunk, int level) {
    return FarVersionDistance(TreeLevelDeparture(crown, trunk, kTreeLevels[level]), 381.0, 0.5);
  };
  EXPECT_NEAR(distance(7.0 / 3.0, 0.35, 1), 93.6, 0.1);
  EXPECT_NEAR(distance(7.0 / 3.0, 0.35, 2), 215.7, 0.1);
  EXPECT_NEAR(distance(1.0, 0.15, 1), 40.1, 0.1);
  EXPECT_NEAR(distance(1.0, 0.15, 2), 92.5, 0.1);
}

}  // namespace
}  // namespace trackbed::render
