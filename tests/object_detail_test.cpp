// Far versions of trees: how far their silhouettes depart from the full version's,
// and from which distance that is below a bound in pixels.
#include "trackbed/sim/object_detail.h"

#include <cmath>

#include <gtest/gtest.h>

namespace trackbed::sim {
namespace {

TEST(ObjectDetailTest, AnInscribedPolygonSagsByRadiusTimesOneMinusCosineOfHalfItsStep) {
  EXPECT_NEAR(InscribedPolygonSag(1.0, 4), 1.0 - std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(InscribedPolygonSag(2.0, 6), 2.0 * (1.0 - std::sqrt(3.0) / 2.0), 1e-15);
  EXPECT_NEAR(InscribedPolygonSag(1.0, 1000), 0.0, 1e-5);
}

TEST(ObjectDetailTest, CoarserLevelsDepartMoreAndTheFullLevelNotAtAll) {
  EXPECT_EQ(TreeLevelExtraSag(2.0, 0.3, kTreeLevels[0]), 0.0);
  double previous = 0.0;
  for (std::size_t l = 1; l < kTreeLevels.size(); ++l) {
    const double extra = TreeLevelExtraSag(2.0, 0.3, kTreeLevels[l]);
    EXPECT_GT(extra, previous) << "level " << l;
    previous = extra;
  }
  // The crown's slices (16 → 12 facets around) are its coarser step at level 1:
  // 2.0 · (cos(π/16) − cos(π/12)).
  EXPECT_NEAR(TreeLevelExtraSag(2.0, 0.3, kTreeLevels[1]),
              2.0 * (std::cos(M_PI / 16) - std::cos(M_PI / 12)), 1e-15);
  // Without a crown, the trunk alone: 24 → 8 facets around at level 2.
  EXPECT_NEAR(TreeLevelExtraSag(0.0, 0.3, kTreeLevels[2]),
              0.3 * (std::cos(M_PI / 24) - std::cos(M_PI / 8)), 1e-15);
}

TEST(ObjectDetailTest, TheLargestParkTreesCoarsenFromTensOfMetres) {
  // A 7 m tree's crown (radius 7/3 m) and trunk (0.35 m) seen at f = 381 px with
  // half a pixel allowed: 12 facets from 26 m, 8 from 101 m.
  const double crown = 7.0 / 3.0, trunk = 0.35;
  EXPECT_NEAR(FarVersionDistance(TreeLevelExtraSag(crown, trunk, kTreeLevels[1]), 381.0, 0.5), 26.4,
              0.1);
  EXPECT_NEAR(FarVersionDistance(TreeLevelExtraSag(crown, trunk, kTreeLevels[2]), 381.0, 0.5),
              101.1, 0.1);
}

}  // namespace
}  // namespace trackbed::sim
