// Teach & repeat scores on hand-made paths: lateral error (signed, RMS, max), end-point
// error, autonomy, the progressive projection on a route that comes back on itself, and
// the recovery rates of Choi & Ha's Table 1 (mean of per-place rates 86.18 %, pooled 531 of
// 605).
#include "trackbed/teach_repeat/teach_repeat_metrics.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/teach_repeat/running_repeat_score.h"

namespace trackbed::teach_repeat {
namespace {

std::vector<Eigen::Vector2d> Line(double x0, double x1, double y, int n) {
  std::vector<Eigen::Vector2d> path;
  for (int i = 0; i < n; ++i) path.emplace_back(x0 + (x1 - x0) * i / (n - 1), y);
  return path;
}

TEST(RepeatPathMetricsTest, ConstantOffsetGivesThatLateralError) {
  const std::vector<Eigen::Vector2d> taught = Line(0.0, 4.0, 0.0, 5);  // vertices every 1 m
  const std::vector<Eigen::Vector2d> left = Line(0.0, 4.0, 0.1, 41);
  const std::vector<PathProjection> p = ProjectOntoPath(taught, left);
  ASSERT_EQ(p.size(), left.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR(p[i].lateral_m, 0.1, 1e-12);  // left of the path: positive
    EXPECT_NEAR(p[i].arc_length_m, 0.1 * i, 1e-12);
  }
  EXPECT_NEAR(ProjectOntoPath(taught, Line(0.0, 4.0, -0.1, 3))[1].lateral_m, -0.1, 1e-12);

  const RepeatPathMetrics m = EvaluateRepeatPath(taught, left, true);
  EXPECT_EQ(m.samples, 41u);
  EXPECT_NEAR(m.taught_length_m, 4.0, 1e-12);
  EXPECT_NEAR(m.lateral_rms_m, 0.1, 1e-12);
  EXPECT_NEAR(m.lateral_max_m, 0.1, 1e-12);
  EXPECT_NEAR(m.end_point_error_m, 0.1, 1e-12);
  EXPECT_NEAR(m.covered_m, 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.autonomy, 1.0);
}

TEST(RepeatPathMetricsTest, RmsMaxAndEndPointOfAConvergingRepeat) {
  const std::vector<Eigen::Vector2d> taught = Line(0.0, 3.0, 0.0, 2);
  // Lateral errors 0.2, 0.1, 0.0, −0.1 at x = 0, 1, 2, 3 (then stopping short by 0.2 m).
  const std::vector<Eigen::Vector2d> repeated = {{0.0, 0.2}, {1.0, 0.1}, {2.0, 0.0}, {2.8, -0.1}};
  const RepeatPathMetrics m = EvaluateRepeatPath(taught, repeated, true);
  EXPECT_NEAR(m.lateral_rms_m, std::sqrt((0.04 + 0.01 + 0.0 + 0.01) / 4.0), 1e-12);
  EXPECT_NEAR(m.lateral_max_m, 0.2, 1e-12);
  EXPECT_NEAR(m.end_point_error_m, std::hypot(0.2, 0.1), 1e-12);
  // Started 0.2 m left; over the last metre reached (x >= 1.8): 0.0 and -0.1.
  EXPECT_NEAR(m.lateral_start_m, 0.2, 1e-12);
  EXPECT_NEAR(m.lateral_end_rms_m, std::sqrt((0.0 + 0.01) / 2.0), 1e-12);
}

TEST(RepeatPathMetricsTest, AutonomyIsTheFractionCoveredBeforeAFailure) {
  const std::vector<Eigen::Vector2d> taught = Line(0.0, 10.0, 0.0, 11);
  const std::vector<Eigen::Vector2d> until_failure = Line(0.0, 3.5, 0.05, 36);
  const RepeatPathMetrics failed = EvaluateRepeatPath(taught, until_failure, false);
  EXPECT_FALSE(failed.completed);
  EXPECT_NEAR(failed.covered_m, 3.5, 1e-12);
  EXPECT_NEAR(failed.autonomy, 0.35, 1e-12);
  // Completed: 1, even if the last position falls short of the end.
  EXPECT_DOUBLE_EQ(EvaluateRepeatPath(taught, Line(0.0, 9.9, 0.0, 10), true).autonomy, 1.0);
  // Beyond the end the arc length stays at the end (autonomy clamped to 1).
  EXPECT_DOUBLE_EQ(EvaluateRepeatPath(taught, Line(0.0, 12.0, 0.0, 13), false).autonomy, 1.0);
}

TEST(RepeatPathMetricsTest, ProgressiveProjectionDoesNotJumpToTheOtherLegOfAnOutAndBack) {
  // Out along y = 0 and back along y = 0.3: a repeat on the way out, 0.2 m left of the
  // outward leg, lies nearer the return leg (0.1 m) — the global nearest point would be
  // on the wrong leg.
  std::vector<Eigen::Vector2d> taught = Line(0.0, 5.0, 0.0, 6);
  for (const Eigen::Vector2d& p : Line(5.0, 0.0, 0.3, 6)) taught.push_back(p);
  const std::vector<Eigen::Vector2d> out = Line(0.0, 4.0, 0.2, 9);
  PathProjectionOptions options;
  options.window_m = 1.0;
  const std::vector<PathProjection> p = ProjectOntoPath(taught, out, options);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_NEAR(p[i].lateral_m, 0.2, 1e-12) << i;
    EXPECT_LT(p[i].arc_length_m, 5.0) << i;
  }
  const RepeatPathMetrics m = EvaluateRepeatPath(taught, out, false, options);
  EXPECT_NEAR(m.lateral_max_m, 0.2, 1e-12);
  EXPECT_NEAR(m.covered_m, 4.0, 1e-12);
}

TEST(RepeatPathMetricsTest, BadInputIsRejected) {
  EXPECT_THROW(EvaluateRepeatPath({}, {{0.0, 0.0}}, true), std::invalid_argument);
  EXPECT_THROW(EvaluateRepeatPath({{0.0, 0.0}}, {}, true), std::invalid_argument);
  PathProjectionOptions bad;
  bad.window_m = 0.0;
  try {
    ProjectOntoPath({{0.0, 0.0}}, {{1.0, 0.0}}, bad);
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "window_m");
  }
  // A single taught point: distances to it.
  EXPECT_NEAR(ProjectOntoPath({{0.0, 0.0}}, {{3.0, 4.0}})[0].lateral_m, 5.0, 1e-12);
  EXPECT_DOUBLE_EQ(PolylineLength({{0.0, 0.0}}), 0.0);
}

TEST(RecoveryMetricsTest, ChoiAndHaTableOne) {
  // Features lost and recovered at the 12 places of experiment 1.
  const std::vector<RecoveryCounts> places = {{85, 68}, {16, 15},   {9, 8},     {16, 10},
                                              {37, 21}, {11, 11},   {42, 42},   {49, 42},
                                              {9, 8},   {115, 102}, {107, 106}, {109, 98}};
  const RecoveryMetrics r = EvaluateRecovery(places);
  EXPECT_EQ(r.lost, 605);
  EXPECT_EQ(r.recovered, 531);
  EXPECT_EQ(r.places_with_losses, 12);
  ASSERT_EQ(r.per_place_rate.size(), 12u);
  EXPECT_NEAR(r.per_place_rate[0], 0.8, 1e-12);
  EXPECT_NEAR(r.per_place_rate[3], 0.625, 1e-12);
  EXPECT_NEAR(100.0 * r.mean_rate, 86.18, 0.005);    // the paper's figure
  EXPECT_NEAR(100.0 * r.pooled_rate, 87.77, 0.005);  // 531 / 605
}

TEST(RecoveryMetricsTest, PlacesWithoutLossesHaveNoRate) {
  const RecoveryMetrics r = EvaluateRecovery({{10, 5}, {0, 0}, {4, 4}});
  EXPECT_TRUE(std::isnan(r.per_place_rate[1]));
  EXPECT_EQ(r.places_with_losses, 2);
  EXPECT_NEAR(r.mean_rate, 0.75, 1e-12);
  EXPECT_NEAR(r.pooled_rate, 9.0 / 14.0, 1e-12);
  const RecoveryMetrics none = EvaluateRecovery({{0, 0}});
  EXPECT_TRUE(std::isnan(none.mean_rate));
  EXPECT_TRUE(std::isnan(none.pooled_rate));
  EXPECT_TRUE(std::isnan(EvaluateRecovery({}).mean_rate));
  EXPECT_THROW(EvaluateRecovery({{3, 4}}), std::invalid_argument);
  EXPECT_THROW(EvaluateRecovery({{-1, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::teach_repeat
