// The goal checker every navigator ends a run with (goal_checker.h): both tolerances,
// the heading error across ±π, strictly-inside obstacles, its options.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/goal_checker.h"

namespace trackbed::navigation {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(GoalCheckerTest, ReachedNeedsBothTolerances) {
  const GoalChecker checker({}, {1.0, 2.0, 0.5});  // 0.1 m and 2° by default
  EXPECT_TRUE(checker.Reached({1.0, 2.0, 0.5}));
  EXPECT_TRUE(checker.Reached({1.06, 2.06, 0.5 + 1.5 * kDeg}));  // 0.085 m, 1.5°
  EXPECT_FALSE(checker.Reached({1.0, 2.11, 0.5}));               // 0.11 m off
  EXPECT_FALSE(checker.Reached({1.0, 2.0, 0.5 - 2.5 * kDeg}));   // 2.5° off
}

TEST(GoalCheckerTest, HeadingErrorWrapsAcrossPi) {
  // Goal heading just below π, pose heading just above −π: 1.15° apart, not 358.85°.
  const GoalChecker checker({}, {0.0, 0.0, M_PI - 0.01});
  EXPECT_TRUE(checker.Reached({0.0, 0.0, -M_PI + 0.01}));
}

TEST(GoalCheckerTest, TolerancesComeFromTheOptions) {
  GoalCheckerOptions options;
  options.position_tolerance_m = 0.5;
  options.heading_tolerance_rad = 10.0 * kDeg;
  const GoalChecker checker(options, {0.0, 0.0, 0.0});
  EXPECT_TRUE(checker.Reached({0.4, 0.0, 9.0 * kDeg}));
  EXPECT_FALSE(checker.Reached({0.6, 0.0, 0.0}));
  EXPECT_FALSE(checker.Reached({0.0, 0.0, 11.0 * kDeg}));
}

TEST(GoalCheckerTest, OptionsOfASetupAreItsGoalTolerances) {
  NavigationSetup setup;
  setup.stop_position_tolerance_m = 0.25;
  setup.stop_heading_tolerance_deg = 5.0;
  const GoalCheckerOptions options = GoalCheckerOptionsOf(setup);
  EXPECT_EQ(options.position_tolerance_m, 0.25);
  EXPECT_EQ(options.heading_tolerance_rad, 5.0 * kDeg);
}

TEST(GoalCheckerTest, GoalInObstacleOnlyStrictlyInside) {
  const GoalChecker checker({}, {3.0, 0.0, 0.0});
  EXPECT_FALSE(checker.GoalInObstacle({}));
  EXPECT_TRUE(checker.GoalInObstacle({{{3.2, 0.0}, 0.5}}));
  EXPECT_TRUE(checker.GoalInObstacle({{{0.0, 0.0}, 0.1}, {{3.0, 0.4}, 0.5}}));  // any of them
  EXPECT_FALSE(checker.GoalInObstacle({{{3.5, 0.0}, 0.5}}));  // on the edge: reachable
  EXPECT_FALSE(checker.GoalInObstacle({{{3.0, 0.0}, 0.0}}));  // a point obstacle at the goal
  EXPECT_FALSE(checker.GoalInObstacle({{{4.0, 0.0}, 0.5}}));
}

TEST(GoalCheckerTest, InvalidOptionsNameTheField) {
  GoalCheckerOptions options;
  options.position_tolerance_m = 0.0;
  try {
    GoalChecker checker(options, {});
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "position_tolerance_m");
  }
  options = {};
  options.heading_tolerance_rad = 4.0;
  try {
    options.Validate();
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "heading_tolerance_rad");
  }
}

}  // namespace
}  // namespace trackbed::navigation
