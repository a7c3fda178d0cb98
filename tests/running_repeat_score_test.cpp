// The repeat scored as it goes: the same figures as the batch scores bit for bit, the
// bisected projection the same as a scan of every taught segment, and the end window
// bounded on a long repeat.
#include "trackbed/teach_repeat/running_repeat_score.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/teach_repeat/teach_repeat_metrics.h"

namespace trackbed::teach_repeat {
namespace {

// A wavy loop taught at 1 mm spacing, as a slow teach pass sampled at 100 Hz gives.
std::vector<Eigen::Vector2d> TaughtLoop(int n) {
  std::vector<Eigen::Vector2d> path;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    path.emplace_back(20.0 * std::cos(a) + 0.3 * std::sin(17.0 * a), 12.0 * std::sin(a));
  }
  return path;
}

// The taught loop driven again with a wandering offset, `per_point` samples per taught point.
std::vector<Eigen::Vector2d> Repeated(const std::vector<Eigen::Vector2d>& taught, int per_point,
                                      unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<Eigen::Vector2d> out;
  Eigen::Vector2d offset(0.05, -0.02);
  for (std::size_t i = 0; i + 1 < taught.size(); ++i) {
    for (int j = 0; j < per_point; ++j) {
      offset += Eigen::Vector2d(noise(rng), noise(rng));
      const double t = static_cast<double>(j) / per_point;
      out.push_back(taught[i] + t * (taught[i + 1] - taught[i]) + offset);
    }
  }
  return out;
}

// The projection by a scan of every segment of the taught path, for comparison.
std::vector<PathProjection> ScanEverySegment(const std::vector<Eigen::Vector2d>& taught,
                                             const std::vector<Eigen::Vector2d>& repeated,
                                             double window_m) {
  std::vector<double> arc(taught.size(), 0.0);
  for (std::size_t k = 1; k < taught.size(); ++k)
    arc[k] = arc[k - 1] + (taught[k] - taught[k - 1]).norm();
  std::vector<PathProjection> out;
  double previous = 0.0;
  for (const Eigen::Vector2d& p : repeated) {
    double best_distance = std::numeric_limits<double>::infinity();
    PathProjection best;
    for (std::size_t k = 0; k + 1 < taught.size(); ++k) {
      if (arc[k + 1] < previous - window_m || arc[k] > previous + window_m) continue;
      const Eigen::Vector2d d = taught[k + 1] - taught[k];
      const double length = d.norm();
      const double t =
          length > 0.0 ? std::clamp((p - taught[k]).dot(d) / (length * length), 0.0, 1.0) : 0.0;
      const double distance = (p - (taught[k] + t * d)).norm();
      if (distance < best_distance) {
        best_distance = distance;
        best.arc_length_m = arc[k] + t * length;
        const double side = d.x() * (p - taught[k]).y() - d.y() * (p - taught[k]).x();
        best.lateral_m = side < 0.0 ? -distance : distance;
      }
    }
    out.push_back(best);
    previous = best.arc_length_m;
  }
  return out;
}

TEST(RunningRepeatScoreTest, BisectedProjectionEqualsAScanOfEverySegment) {
  const std::vector<Eigen::Vector2d> taught = TaughtLoop(3000);
  const std::vector<Eigen::Vector2d> repeated = Repeated(taught, 2, 7);
  PathProjectionOptions options;
  options.window_m = 0.5;
  const std::vector<PathProjection> fast = ProjectOntoPath(taught, repeated, options);
  const std::vector<PathProjection> scan = ScanEverySegment(taught, repeated, options.window_m);
  ASSERT_EQ(fast.size(), scan.size());
  for (std::size_t i = 0; i < fast.size(); ++i) {
    ASSERT_EQ(fast[i].arc_length_m, scan[i].arc_length_m) << i;
    ASSERT_EQ(fast[i].lateral_m, scan[i].lateral_m) << i;
  }
}

TEST(RunningRepeatScoreTest, ScoresAsItGoesEqualTheBatchScoresBitForBit) {
  const std::vector<Eigen::Vector2d> taught = TaughtLoop(20000);
  const std::vector<Eigen::Vector2d> repeated = Repeated(taught, 3, 11);
  RunningRepeatScore running(taught);
  for (const Eigen::Vector2d& p : repeated) running.Add(p);
  // The batch scores, computed here from the projections as the scores are defined.
  const std::vector<PathProjection> projections = ProjectOntoPath(taught, repeated);
  for (const bool completed : {true, false}) {
    double sum_sq = 0.0, max_abs = 0.0, covered = 0.0;
    for (const PathProjection& p : projections) {
      sum_sq += p.lateral_m * p.lateral_m;
      max_abs = std::max(max_abs, std::abs(p.lateral_m));
      covered = std::max(covered, p.arc_length_m);
    }
    double end_sq = 0.0;
    int end_n = 0;
    for (const PathProjection& p : projections) {
      if (p.arc_length_m < covered - RepeatPathMetrics::kEndWindowM) continue;
      end_sq += p.lateral_m * p.lateral_m;
      ++end_n;
    }
    const RepeatPathMetrics m = running.Metrics(completed);
    EXPECT_EQ(m.samples, repeated.size());
    EXPECT_EQ(m.lateral_rms_m, std::sqrt(sum_sq / repeated.size()));
    EXPECT_EQ(m.lateral_max_m, max_abs);
    EXPECT_EQ(m.covered_m, covered);
    EXPECT_EQ(m.lateral_start_m, std::abs(projections.front().lateral_m));
    EXPECT_EQ(m.lateral_end_rms_m, std::sqrt(end_sq / end_n));
    EXPECT_EQ(m.end_point_error_m, (repeated.back() - taught.back()).norm());
    EXPECT_EQ(m.completed, completed);
    const RepeatPathMetrics batch = EvaluateRepeatPath(taught, repeated, completed);
    EXPECT_EQ(batch.lateral_rms_m, m.lateral_rms_m);
    EXPECT_EQ(batch.lateral_end_rms_m, m.lateral_end_rms_m);
    EXPECT_EQ(batch.autonomy, m.autonomy);
  }
}

TEST(RunningRepeatScoreTest, EndWindowStaysBoundedOnALongRepeat) {
  // 59 990 positions along a loop of about 103 m (about 580 positions per metre on
  // average, up to 1.7 times that where the ellipse's points are densest): the end window
  // holds the positions of about the last metre, up to twice over before it is compacted.
  const std::vector<Eigen::Vector2d> taught = TaughtLoop(6000);
  RunningRepeatScore running(taught);
  std::size_t largest = 0;
  for (const Eigen::Vector2d& p : Repeated(taught, 10, 3)) {
    running.Add(p);
    largest = std::max(largest, running.end_window_size());
  }
  EXPECT_EQ(running.samples(), 59990u);
  const double per_metre = running.samples() / PolylineLength(taught);
  EXPECT_LT(largest, 2.0 * 1.7 * 1.2 * per_metre * RepeatPathMetrics::kEndWindowM) << per_metre;
  EXPECT_GT(running.Metrics(true).lateral_end_rms_m, 0.0);
}

TEST(RunningRepeatScoreTest, RefusesAnEmptyPathAndScoresWithoutPositions) {
  EXPECT_THROW(RunningRepeatScore({}), std::invalid_argument);
  RunningRepeatScore running(TaughtLoop(10));
  EXPECT_THROW(running.Metrics(true), std::invalid_argument);
  // A single taught point: the distance to it, no arc length.
  RunningRepeatScore point({Eigen::Vector2d(1.0, 1.0)});
  EXPECT_EQ(point.Add({4.0, 5.0}).lateral_m, 5.0);
  EXPECT_EQ(point.Metrics(false).autonomy, 0.0);
}

}  // namespace
}  // namespace trackbed::teach_repeat
