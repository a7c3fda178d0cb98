// Teach & repeat through a curve whose inside shows nothing (the lab route's 90° curve,
// docs/teach_repeat.md "On the simulated robot"): both repeaters, and the 2D progress fit
// that switches their milestones. The synthetic corridor with the left half of every
// image blanked, so that all features lie on the outside of a left curve.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "teach_repeat_test_scene.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/perception/feature_tracker.h"
#include "trackbed/teach_repeat/funnel_lane_controller.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/milestone_localizer_3d.h"
#include "trackbed/teach_repeat/milestone_switch.h"

namespace trackbed::teach_repeat {
namespace {

using geometry::Pose2;
using navigation::IntegrateTwist;  // the robot of these tests drives the twist exactly
using testing::CameraPose;
using testing::CorridorScene;
using testing::TestCamera;

constexpr double kDeg = M_PI / 180.0;
constexpr double kRadius = 4.0;  // [m] of the taught left curve
constexpr double kStep = 0.02;   // [m] of path per teach image

/// The taught pose `s` metres along a left arc of kRadius from the origin.
Pose2 ArcPose(double s) {
  const double a = s / kRadius;
  return {kRadius * std::sin(a), kRadius * (1.0 - std::cos(a)), a};
}

/// The scene's image with its left half a flat grey: nothing to track there.
cv::Mat RightHalfOnly(const CorridorScene& scene, const Pose2& pose) {
  cv::Mat image = scene.Render(CameraPose(pose));
  image(cv::Rect(0, 0, image.cols / 2, image.rows)).setTo(cv::Scalar(128));
  return image;
}

TeachMap TeachArc(const CorridorScene& scene, TeachMode mode, int images) {
  MilestoneBuilderOptions options;
  options.mode = mode;
  options.interval_images = 10;
  MilestoneBuilder builder(TestCamera(), options);
  for (int k = 0; k < images; ++k) {
    const Pose2 pose = ArcPose(kStep * k);
    builder.AddImage(RightHalfOnly(scene, pose), 0.1 * k, pose);
  }
  return builder.Finish();
}

struct CurveResult {
  RepeatCommand last;
  double worst_lateral_m = 0.0;  // largest |distance from the arc|
  Pose2 end;
};

CurveResult RepeatArc(const CorridorScene& scene, Repeater* repeater, int max_frames) {
  CurveResult r;
  Pose2 pose = ArcPose(0.0);
  for (int k = 0; k < max_frames; ++k) {
    r.last = repeater->Update(RightHalfOnly(scene, pose), 0.1 * k);
    if (r.last.status != RepeatStatus::kDriving) break;
    const double lateral = std::hypot(pose.x, pose.y - kRadius) - kRadius;
    r.worst_lateral_m = std::max(r.worst_lateral_m, std::abs(lateral));
    pose = IntegrateTwist(pose, r.last.twist, 0.1);
  }
  r.end = pose;
  return r;
}

TEST(MilestoneProgressTest, FeaturesOnOneSideGiveTheProgressAndTheHeadingError) {
  // A straight teach; the second milestone (images 10–20, x = 0.2–0.4 m) seen from
  // places along it, only its features right of the centre used.
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.interval_images = 10;
  MilestoneBuilder builder(TestCamera(), options);
  for (int k = 0; k < 31; ++k) {
    const Pose2 pose{kStep * k, 0.0, 0.0};
    builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose);
  }
  const TeachMap map = builder.Finish();
  const Milestone& m = map.milestones.at(1);
  perception::FeatureTracker tracker;
  perception::TrackingPyramid key, current;
  tracker.BuildPyramid(m.key_image, &key);
  std::vector<cv::Point2f> first;
  for (const MilestoneFeature& f : m.features) first.push_back(f.first_px);
  for (double yaw_deg : {0.0, 2.0}) {
    for (double p_true : {0.0, 0.5, 1.0, 1.2}) {
      const Pose2 pose{0.2 + 0.2 * p_true, 0.0, yaw_deg * kDeg};
      tracker.BuildPyramid(scene.Render(CameraPose(pose)), &current);
      std::vector<cv::Point2f> now;
      std::vector<perception::TrackStatus> status;
      tracker.Track(key, current, first, &now, &status);
      std::vector<bool> use;
      int right = 0;
      for (std::size_t i = 0; i < first.size(); ++i) {
        use.push_back(status[i] == perception::TrackStatus::kTracked &&
                      m.features[i].first_px.x > TestCamera().cx);
        right += use.back() ? 1 : 0;
      }
      ASSERT_GE(right, 12);
      const MilestoneProgress p = EstimateMilestoneProgress(TestCamera(), m, now, use);
      ASSERT_TRUE(p.valid) << "p " << p_true << ", yaw " << yaw_deg;
      // Beyond the destination fewer features remain (17 at 1.2 with the yaw).
      EXPECT_NEAR(p.progress, p_true, p_true > 1.0 ? 0.15 : 0.07) << "yaw " << yaw_deg;
      // A yaw to the left moves every bearing right by fx·yaw (13.3 px per 2°).
      EXPECT_NEAR(p.heading_px, TestCamera().fx * yaw_deg * kDeg, 3.0) << "p " << p_true;
    }
  }
  // Without flow (every feature where it was) the progress cannot be measured.
  std::vector<cv::Point2f> same;
  for (const MilestoneFeature& f : m.features) same.push_back(f.first_px);
  Milestone still = m;
  for (MilestoneFeature& f : still.features) f.last_px = f.first_px;
  EXPECT_FALSE(
      EstimateMilestoneProgress(TestCamera(), still, same, std::vector<bool>(same.size(), true))
          .valid);
}

TEST(CurveRepeatTest, TwoDFollowsALeftCurveSeenOnlyOnItsOutside) {
  // Without the progress switch and the heading correction this repeat never switches
  // past its first milestone (the outward mean error of one-sided features is zero),
  // drives straight on out of the curve and is lost 1.8 m off it.
  const CorridorScene scene;
  const int images = 101;  // 2 m, 29° of turn
  FunnelLaneOptions options;
  options.forward_speed_mps = 0.2;
  options.turn_rate_radps = 10.0 * kDeg;
  const TeachMap map = TeachArc(scene, TeachMode::k2d, images);
  FunnelLaneRepeater repeater(map, options);
  const CurveResult r = RepeatArc(scene, &repeater, 200);
  options.switch_by_progress = false;
  options.heading_correction = false;
  FunnelLaneRepeater without(map, options);
  const CurveResult w = RepeatArc(scene, &without, 200);
  std::printf("2D without progress and heading: %s, worst lateral %.3f m, milestone %d of %zu\n",
              ToString(w.last.status), w.worst_lateral_m, w.last.milestone, map.milestones.size());
  const Pose2 end = ArcPose(kStep * (images - 1));
  std::printf("2D, one-sided curve: %s, worst lateral %.3f m, end %.3f m from the taught end\n",
              ToString(r.last.status), r.worst_lateral_m,
              std::hypot(r.end.x - end.x, r.end.y - end.y));
  ASSERT_EQ(r.last.status, RepeatStatus::kFinished);
  EXPECT_LT(r.worst_lateral_m, 0.05);
  EXPECT_LT(std::hypot(r.end.x - end.x, r.end.y - end.y), 0.1);
  // The two changes are what make the difference.
  EXPECT_NE(w.last.status, RepeatStatus::kFinished);
  EXPECT_GT(w.worst_lateral_m, 0.5);
}

TEST(CurveRepeatTest, ThreeDFollowsALeftCurveWithTheCurvatureFedForward) {
  // Without the feed-forward the law needs a standing error to turn at all, and the
  // repeat ran up to 0.15 m outside this curve (0.04 m with it; the camera, 0.2 m
  // ahead of the body, follows the taught camera path).
  const CorridorScene scene;
  const int images = 101;
  Localizer3dOptions options;
  options.forward_speed_mps = 0.2;
  options.max_yaw_rate_radps = 10.0 * kDeg;
  const TeachMap map = TeachArc(scene, TeachMode::k3d, images);
  MilestoneLocalizer3d repeater(map, options);
  const CurveResult r = RepeatArc(scene, &repeater, 200);
  options.curvature_feed_forward = false;
  MilestoneLocalizer3d without(map, options);
  const CurveResult w = RepeatArc(scene, &without, 200);
  std::printf("3D without the feed-forward: worst lateral %.3f m\n", w.worst_lateral_m);
  const Pose2 end = ArcPose(kStep * (images - 1));
  std::printf("3D, one-sided curve: %s, worst lateral %.3f m, end %.3f m from the taught end\n",
              ToString(r.last.status), r.worst_lateral_m,
              std::hypot(r.end.x - end.x, r.end.y - end.y));
  ASSERT_EQ(r.last.status, RepeatStatus::kFinished);
  EXPECT_LT(r.worst_lateral_m, 0.05);
  EXPECT_LT(std::hypot(r.end.x - end.x, r.end.y - end.y), 0.1);
  // The feed-forward is what makes the difference.
  EXPECT_GT(w.worst_lateral_m, 2.0 * r.worst_lateral_m);
}

}  // namespace
}  // namespace trackbed::teach_repeat
