// Sub-goal geometry and switching (Jung & Kim 2014, §2.4) against hand-computed cases:
// tangent and intersection sub-goals, the blocking test, clusters, the switcher.
#include <cmath>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/subgoal_planner.h"

namespace trackbed::navigation {
namespace {

constexpr double kDeg = M_PI / 180.0;

void ExpectNear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double tol = 1e-9) {
  EXPECT_NEAR(a.x(), b.x(), tol);
  EXPECT_NEAR(a.y(), b.y(), tol);
}

TEST(TangentSubgoalsTest, RobotOutsideTheCircleHandComputed) {
  // Robot at the origin, circle of radius 1 at (2, 0): θ1 = 0, θ2 = asin(1/2) = 30°, the
  // tangents have length √3, the tangent points are √3·(cos 30°, ±sin 30°) = (1.5, ±√3/2).
  const std::optional<SubgoalPair> s = TangentSubgoals({0, 0}, {2, 0}, 1.0);
  ASSERT_TRUE(s);
  ExpectNear(s->left_point, {1.5, std::sqrt(3.0) / 2});
  ExpectNear(s->right_point, {1.5, -std::sqrt(3.0) / 2});
  ExpectNear(s->left, {1.8, 1.2 * std::sqrt(3.0) / 2});  // 1.2 × (tangent − robot)
  ExpectNear(s->right, {1.8, -1.2 * std::sqrt(3.0) / 2});
}

TEST(TangentSubgoalsTest, LeftIsCounterClockwiseInAnyFrame) {
  // Looking north from (1, 1) at a circle around (1, 3): left is west.
  const std::optional<SubgoalPair> s = TangentSubgoals({1, 1}, {1, 3}, 1.0);
  ASSERT_TRUE(s);
  ExpectNear(s->left_point, {1 - std::sqrt(3.0) / 2, 2.5});
  ExpectNear(s->right_point, {1 + std::sqrt(3.0) / 2, 2.5});
  // Tangent ⟂ radius at the tangent point.
  EXPECT_NEAR((s->left_point - Eigen::Vector2d(1, 1)).dot(s->left_point - Eigen::Vector2d(1, 3)),
              0.0, 1e-12);
}

TEST(TangentSubgoalsTest, NoTangentsFromInsideTheCircle) {
  EXPECT_FALSE(TangentSubgoals({0, 0}, {0.5, 0}, 1.0));
  EXPECT_FALSE(TangentSubgoals({0, 0}, {1.0, 0}, 1.0));
}

TEST(IntersectionSubgoalsTest, RobotInsideTheCircleHandComputed) {
  // Robot circle of radius 1 at (0, 0), obstacle circle of radius 1 at (0.8, 0) (the robot
  // is inside it): the radical line is x = (0.8² + 1 − 1)/(2·0.8) = 0.4, and
  // y = ±√(1 − 0.4²) = ±√0.84.
  const std::optional<SubgoalPair> s = IntersectionSubgoals({0, 0}, 1.0, {0.8, 0}, 1.0);
  ASSERT_TRUE(s);
  const double y = std::sqrt(0.84);
  ExpectNear(s->left_point, {0.4, y});
  ExpectNear(s->right_point, {0.4, -y});
  ExpectNear(s->left, {0.48, 1.2 * y});
  ExpectNear(s->right, {0.48, -1.2 * y});
  EXPECT_NEAR(s->left_point.norm(), 1.0, 1e-12);  // on the robot's circle
  EXPECT_NEAR((s->left_point - Eigen::Vector2d(0.8, 0)).norm(), 1.0, 1e-12);
}

TEST(IntersectionSubgoalsTest, NoIntersectionWhenCirclesAreApartOrNested) {
  EXPECT_FALSE(IntersectionSubgoals({0, 0}, 1.0, {2.5, 0}, 1.0));
  EXPECT_FALSE(IntersectionSubgoals({0, 0}, 1.0, {0.1, 0}, 0.5));
}

TEST(AvoidanceConeTest, TangentAndIntersectionHalfWidths) {
  const AvoidanceCone outside = AvoidanceConeOf({0, 0}, 1.0, Circle{{2, 0}, 0.0}, 1.0);
  EXPECT_EQ(outside.kind, AvoidanceCone::Kind::kTangent);
  EXPECT_NEAR(outside.half_width_rad, 30 * kDeg, 1e-12);
  EXPECT_NEAR(outside.edge_distance_m, std::sqrt(3.0), 1e-12);
  const AvoidanceCone inside = AvoidanceConeOf({0, 0}, 1.0, Circle{{0.8, 0}, 0.0}, 1.0);
  EXPECT_EQ(inside.kind, AvoidanceCone::Kind::kIntersection);
  EXPECT_NEAR(inside.half_width_rad, std::atan2(std::sqrt(0.84), 0.4), 1e-12);  // θ4
  EXPECT_NEAR(inside.edge_distance_m, 1.0, 1e-12);
  // A physical radius adds to the safety radius: R = 0.5 at (3, 0) is a circle of 1.5.
  const AvoidanceCone big = AvoidanceConeOf({0, 0}, 1.0, Circle{{3, 0}, 0.5}, 1.0);
  EXPECT_NEAR(big.half_width_rad, 30 * kDeg, 1e-12);
  EXPECT_EQ(AvoidanceConeOf({0, 0}, 1.0, Circle{{0.1, 0}, 0.3}, 1.0).kind,
            AvoidanceCone::Kind::kEnclosing);
}

TEST(BlocksTest, OutsideTheCircleBetweenTheTangents) {
  const Circle point{{1.8, 0}, 0.0};  // θ2 = asin(1/1.8) = 33.75°
  EXPECT_TRUE(Blocks({0, 0, 0}, point, 1.0));
  EXPECT_TRUE(Blocks({0, 0, 30 * kDeg}, point, 1.0));
  EXPECT_FALSE(Blocks({0, 0, 40 * kDeg}, point, 1.0));
  EXPECT_FALSE(Blocks({0, 0, M_PI}, point, 1.0));
}

TEST(BlocksTest, OnlyWhenTheTwoCirclesMeet) {
  EXPECT_FALSE(Blocks({0, 0, 0}, Circle{{2.1, 0}, 0.0}, 1.0));  // 2.1 > 2·d_max
  EXPECT_TRUE(Blocks({0, 0, 0}, Circle{{2.0, 0}, 0.0}, 1.0));
  EXPECT_TRUE(Blocks({0, 0, 0}, Circle{{2.1, 0}, 0.2}, 1.0));  // reach 2·d_max + R = 2.2
}

TEST(BlocksTest, InsideTheCircleBetweenTheIntersectionLines) {
  // Obstacle circle of radius 1 at (0.8, 0): x = 0.64/1.6 = 0.4, θ4 = atan2(√0.84, 0.4) = 66.4°.
  const Circle point{{0.8, 0}, 0.0};
  EXPECT_TRUE(Blocks({0, 0, 60 * kDeg}, point, 1.0));
  EXPECT_FALSE(Blocks({0, 0, 70 * kDeg}, point, 1.0));
  EXPECT_FALSE(Blocks({0, 0, -120 * kDeg}, point, 1.0));
  EXPECT_TRUE(Blocks({0, 0, M_PI}, Circle{{0.1, 0}, 0.3}, 1.0));  // inside the obstacle
}

TEST(ClusterLabelsTest, OverlappingSafetyCirclesChainIntoOneCluster) {
  const std::vector<Circle> obstacles = {
      {{0, 0}, 0.0}, {{1.9, 0}, 0.0}, {{3.8, 0}, 0.0}, {{10, 0}, 0.0}, {{12.1, 0}, 0.0}};
  const std::vector<int> labels = ClusterLabels(obstacles, std::vector<double>(5, 1.0));
  EXPECT_EQ(labels, (std::vector<int>{0, 0, 0, 1, 2}));
  // A larger physical radius closes the gap.
  const std::vector<Circle> fat = {{{10, 0}, 0.0}, {{12.1, 0}, 0.2}};
  EXPECT_EQ(ClusterLabels(fat, {1.0, 1.0}), (std::vector<int>{0, 0}));
}

TEST(WallCirclesTest, ChainSpacingIsAtMostTheLimitAndEndsAreExact) {
  const std::vector<Circle> wall = WallCircles({0, 0}, {2.5, 0}, 0.1, 1.0);
  ASSERT_EQ(wall.size(), 4u);
  ExpectNear(wall.front().centre, {0, 0});
  ExpectNear(wall.back().centre, {2.5, 0});
  for (std::size_t k = 1; k < wall.size(); ++k) {
    EXPECT_LE((wall[k].centre - wall[k - 1].centre).norm(), 1.0 + 1e-12);
    EXPECT_EQ(wall[k].radius_m, 0.1);
  }
  EXPECT_EQ(WallCircles({1, 1}, {1, 1}, 0.1, 1.0).size(), 1u);
  EXPECT_THROW(WallCircles({0, 0}, {1, 0}, 0.1, 0.0), std::invalid_argument);
}

TEST(SubgoalSwitcherTest, PaperGeometryMakesTheLeftTangentSubgoal) {
  // The paper's right-hand scene: goal [5 5 90°], point obstacle at [2.5 2.5]; the robot
  // drives along the diagonal. At (1.2, 1.2) (1.84 m away) the circles meet and the
  // heading points at the obstacle; both candidates are equally near the goal: left.
  SubgoalSwitcher switcher({}, {5, 5, 90 * kDeg});
  const std::vector<Circle> obstacles = {{{2.5, 2.5}, 0.0}};
  EXPECT_FALSE(switcher.Update({0.5, 0.5, 45 * kDeg}, obstacles).subgoal_active);  // 2.83 m
  const ActiveTarget t = switcher.Update({1.2, 1.2, 45 * kDeg}, obstacles);
  ASSERT_TRUE(t.new_subgoal);
  EXPECT_TRUE(t.subgoal_active);
  const SubgoalPair expected = *TangentSubgoals({1.2, 1.2}, {2.5, 2.5}, 1.0);
  ExpectNear({t.pose.x, t.pose.y}, expected.left);
  ASSERT_EQ(switcher.subgoals().size(), 1u);
  EXPECT_TRUE(switcher.subgoals()[0].left);
  EXPECT_FALSE(switcher.subgoals()[0].reached);

  // Reached, and from there (heading along the tangent) nothing blocks: back to the goal.
  const double yaw = std::atan2(expected.left.y() - 1.2, expected.left.x() - 1.2);
  const ActiveTarget back = switcher.Update({expected.left.x(), expected.left.y(), yaw}, obstacles);
  EXPECT_FALSE(back.subgoal_active);
  ExpectNear({back.pose.x, back.pose.y}, {5, 5});
  EXPECT_TRUE(switcher.subgoals()[0].reached);
}

TEST(SubgoalSwitcherTest, ANearerGoalSideWins) {
  // Obstacle slightly right of the line to the goal: going left is shorter.
  SubgoalSwitcher switcher({}, {6, 0.3, 0});
  const ActiveTarget t = switcher.Update({0.5, 0.0, std::atan2(0.3, 5.5)}, {{{2.0, -0.2}, 0.0}});
  ASSERT_TRUE(t.new_subgoal);
  const SubgoalPair c = *TangentSubgoals({0.5, 0}, {2.0, -0.2}, 1.0);
  ExpectNear({t.pose.x, t.pose.y}, c.left);
}

TEST(SubgoalSwitcherTest, HeadingsSweptWhileTurningInPlaceDoNotTrigger) {
  SubgoalSwitcher switcher({}, {5, 5, 0});
  // Heading 0° points at the obstacle, but the robot will turn to 45° before driving.
  EXPECT_FALSE(switcher.Update({0, 0, 0}, {{{1.5, 0}, 0.0}}).new_subgoal);
}

TEST(SubgoalSwitcherTest, AnObstacleBeyondTheGoalDoesNotBlock) {
  // The paper's test alone would trigger (circles meet, heading into it); the goal lies
  // before the obstacle and the way to it is clear.
  const Circle wall_post{{1.9, 0}, 0.1};
  EXPECT_TRUE(Blocks({0, 0, 0}, wall_post, 1.0));
  SubgoalSwitcher switcher({}, {1.0, 0, 0});
  EXPECT_FALSE(switcher.Update({0, 0, 0}, {wall_post}).new_subgoal);
}

TEST(SubgoalSwitcherTest, ObstaclesNearTheGoalGetASmallerMargin) {
  const std::vector<Circle> obstacles = {{{10.8, 0}, 0.1}, {{4, 4}, 0.3}};
  const std::vector<double> margins = SafetyMargins(obstacles, {10, 0}, {});
  EXPECT_NEAR(margins[0], 0.6, 1e-12);  // surface 0.7 m from the goal, less 0.1 m
  EXPECT_EQ(margins[1], 1.0);
}

TEST(SubgoalSwitcherTest, ARingAroundTheRobotLeavesNoWayAround) {
  std::vector<Circle> ring;
  for (int k = 0; k < 20; ++k) {
    ring.push_back({{1.5 * std::cos(k * M_PI / 10), 1.5 * std::sin(k * M_PI / 10)}, 0.1});
  }
  SubgoalSwitcher switcher({}, {5, 0, 0});
  const ActiveTarget t = switcher.Update({0, 0, 0}, ring);
  EXPECT_TRUE(t.no_way_around);
  EXPECT_FALSE(t.subgoal_active);
  EXPECT_TRUE(switcher.subgoals().empty());
}

TEST(SubgoalSwitcherTest, RejectsInvalidOptionsNamingTheField) {
  SubgoalOptions options;
  options.subgoal_scale = 0.5;
  try {
    SubgoalSwitcher switcher(options, {});
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "subgoal_scale");
  }
}

}  // namespace
}  // namespace trackbed::navigation
