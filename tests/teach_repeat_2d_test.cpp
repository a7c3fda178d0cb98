// Repeat 2D (Chen & Birchfield 2006): the funnel-lane rules on hand-made f_c/f_d cases, the
// bang-bang vote, the error-minimum switch, and closed kinematic loops over synthetic
// images — a repeat from the taught start keeps to the path, one started 0.2 m and 5° off
// converges toward it — plus loss of features (blank images, an occluder) and input
// validation.
#include "trackbed/teach_repeat/funnel_lane_controller.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "teach_repeat_test_scene.h"
#include "trackbed/common/option_error.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/teach_repeat/funnel_lane_vote.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/milestone_localizer_3d.h"
#include "trackbed/teach_repeat/milestone_switch.h"
#include "trackbed/teach_repeat/repeater_factory.h"

namespace trackbed::teach_repeat {
namespace {

using geometry::Pose2;
using navigation::IntegrateTwist;  // the robot of these tests drives the twist exactly
using testing::CameraPose;
using testing::CorridorScene;
using testing::TestCamera;

constexpr double kDeg = M_PI / 180.0;

// ---------------------------------------------------------------------------------------
// The rules (Choi & Ha 2011 eq. 1; docs/teach_repeat.md).

TEST(FunnelLaneVoteTest, RightWhenTheFeatureIsRightOfCentreAndItsDestinationLeftOfIt) {
  EXPECT_EQ(FunnelLaneVote(10.0, -5.0), TurnVote::kRight);  // f_c > 0 and f_d < 0
  EXPECT_EQ(FunnelLaneVote(0.5, -200.0), TurnVote::kRight);
}

TEST(FunnelLaneVoteTest, RightWhenTheFeatureIsRightOfCentreBeyondItsDestination) {
  EXPECT_EQ(FunnelLaneVote(50.0, 30.0), TurnVote::kRight);  // f_c > 0 and f_c > f_d
  EXPECT_EQ(FunnelLaneVote(300.0, 299.0), TurnVote::kRight);
}

TEST(FunnelLaneVoteTest, LeftWhenTheFeatureIsLeftOfCentreAndItsDestinationRightOfIt) {
  EXPECT_EQ(FunnelLaneVote(-10.0, 5.0), TurnVote::kLeft);  // f_c < 0 and f_d > 0
  EXPECT_EQ(FunnelLaneVote(-0.5, 200.0), TurnVote::kLeft);
}

TEST(FunnelLaneVoteTest, LeftWhenTheFeatureIsLeftOfCentreBeyondItsDestination) {
  EXPECT_EQ(FunnelLaneVote(-50.0, -30.0), TurnVote::kLeft);  // f_c < 0 and f_c < f_d
  EXPECT_EQ(FunnelLaneVote(-300.0, -299.0), TurnVote::kLeft);
}

TEST(FunnelLaneVoteTest, StraightInsideTheFunnel) {
  // Between the image centre and the destination, on either side.
  EXPECT_EQ(FunnelLaneVote(30.0, 50.0), TurnVote::kStraight);
  EXPECT_EQ(FunnelLaneVote(-30.0, -50.0), TurnVote::kStraight);
  EXPECT_EQ(FunnelLaneVote(50.0, 50.0), TurnVote::kStraight);
  EXPECT_EQ(FunnelLaneVote(0.0, 40.0), TurnVote::kStraight);
  EXPECT_EQ(FunnelLaneVote(0.0, -40.0), TurnVote::kStraight);
}

TEST(FunnelLaneVoteTest, TurningTheRightWayMovesTheFeatureBackIntoItsFunnel) {
  // A small right turn δ moves every feature left by about fx·δ; for every "right" case
  // that brings f_c toward f_d, and likewise for "left".
  const double fx = TestCamera().fx, delta = 0.1 * kDeg;
  auto turn = [&](double f, double yaw) { return fx * std::tan(std::atan(f / fx) - yaw); };
  for (double fd : {-200.0, -50.0, -5.0, 5.0, 50.0, 200.0}) {
    for (double fc : {-250.0, -100.0, -20.0, -1.0, 1.0, 20.0, 100.0, 250.0}) {
      const TurnVote v = FunnelLaneVote(fc, fd);
      if (v == TurnVote::kStraight) continue;
      const double after = turn(fc, v == TurnVote::kRight ? delta : -delta);
      EXPECT_LT(std::abs(after - fd), std::abs(fc - fd)) << "f_c " << fc << " f_d " << fd;
    }
  }
}

TEST(DecideTurnTest, BangBangOnTheNetVote) {
  EXPECT_EQ(DecideTurn({0, 0, 0}, 0.1), TurnVote::kStraight);
  EXPECT_EQ(DecideTurn({0, 0, 50}, 0.1), TurnVote::kStraight);
  // left, right, straight
  EXPECT_EQ(DecideTurn({2, 20, 10}, 0.1), TurnVote::kRight);
  EXPECT_EQ(DecideTurn({20, 2, 10}, 0.1), TurnVote::kLeft);
  // A net vote of 3 in 40 (7.5 %) is below a 10 % threshold, above a 5 % one.
  EXPECT_EQ(DecideTurn({5, 8, 27}, 0.1), TurnVote::kStraight);
  EXPECT_EQ(DecideTurn({5, 8, 27}, 0.05), TurnVote::kRight);
  EXPECT_EQ(DecideTurn({8, 5, 27}, 0.05), TurnVote::kLeft);
  EXPECT_EQ(DecideTurn({1, 0, 0}, 0.0), TurnVote::kLeft);
}

TEST(ErrorMinimumDetectorTest, SwitchesOnceTheErrorRisesPastTheHysteresis) {
  ErrorMinimumDetector d(1.0);
  const std::vector<double> error = {10.0, 8.0, 6.0, 4.5, 3.0, 2.2, 2.5, 2.9, 3.1, 3.5, 4.0};
  std::size_t passed_at = error.size();
  for (std::size_t k = 0; k < error.size(); ++k) {
    if (d.Update(error[k]) && passed_at == error.size()) passed_at = k;
  }
  EXPECT_EQ(passed_at, 9u);  // 3.5 > 2.2 + 1.0; 3.1 was not
  EXPECT_DOUBLE_EQ(d.minimum(), 2.2);
  EXPECT_TRUE(d.Update(0.0));  // stays passed until Reset
  d.Reset();
  EXPECT_FALSE(d.Update(5.0));
  EXPECT_FALSE(d.Update(5.9));  // noise within the hysteresis
  EXPECT_FALSE(d.Update(std::nan("")));
  EXPECT_TRUE(d.Update(6.1));
  EXPECT_THROW(ErrorMinimumDetector(-1.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// Closed loop over synthetic images.

/// A straight teach along the corridor's axis, 2 cm per image (`images` images: 151 for
/// 3 m), milestones every 10 images; taught once per length and shared by the tests.
const TeachMap& TeachStraight(const CorridorScene& scene, int images = 151) {
  static std::map<int, TeachMap> cache;
  auto it = cache.find(images);
  if (it == cache.end()) {
    MilestoneBuilderOptions options;
    options.interval_images = 10;
    MilestoneBuilder builder(TestCamera(), options);
    for (int k = 0; k < images; ++k) {
      const Pose2 pose{0.02 * k, 0.0, 0.0};
      builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose);
    }
    it = cache.emplace(images, builder.Finish()).first;
  }
  return it->second;
}

FunnelLaneOptions FastRepeat() {
  FunnelLaneOptions o;
  o.forward_speed_mps = 0.2;  // 2 cm per frame at 10 Hz: a short test
  o.turn_rate_radps = 10.0 * kDeg;
  return o;
}

struct LoopResult {
  std::vector<Pose2> poses;
  std::vector<int> milestones;
  RepeatCommand last;
};

/// The robot integrates its commanded twist for 0.1 s per frame; the camera sees the scene.
LoopResult RunLoop(const CorridorScene& scene, Repeater* repeater, Pose2 start, int max_frames) {
  LoopResult r;
  Pose2 pose = start;
  for (int k = 0; k < max_frames; ++k) {
    r.poses.push_back(pose);
    r.last = repeater->Update(scene.Render(CameraPose(pose)), 0.1 * k);
    r.milestones.push_back(r.last.milestone);
    if (r.last.status != RepeatStatus::kDriving) break;
    pose = IntegrateTwist(pose, r.last.twist, 0.1);
  }
  return r;
}

TEST(FunnelLaneRepeaterTest, RepeatFromTheTaughtStartKeepsToThePathAndSwitchesOnTime) {
  // On the path the mean x-error is smallest at the destination image: the switch comes
  // within a few frames after it (the hysteresis), in both readings of the error; the
  // measured progress (the default) reaches 1 there.
  const CorridorScene scene;
  const TeachMap& map = TeachStraight(scene, 81);  // 1.6 m
  for (int variant = 0; variant < 3; ++variant) {
    FunnelLaneOptions options = FastRepeat();
    options.switch_by_progress = variant == 0;
    options.switch_error = variant == 2 ? SwitchError::kMeanAbsolute : SwitchError::kMeanOutward;
    FunnelLaneRepeater repeater(map, options);
    const LoopResult r = RunLoop(scene, &repeater, {}, 200);
    ASSERT_EQ(r.last.status, RepeatStatus::kFinished);
    double worst = 0.0;
    for (const Pose2& p : r.poses) worst = std::max(worst, std::abs(p.y));
    EXPECT_LT(worst, 0.03);
    EXPECT_NEAR(r.poses.back().x, 1.6, 0.1);
    std::printf("from the start: finished at x = %.3f m, worst |y| %.3f m\n", r.poses.back().x,
                worst);
    // Milestones are visited in order, each once, and switched near their destinations.
    EXPECT_EQ(r.milestones.back(), static_cast<int>(map.milestones.size()) - 1);
    for (std::size_t k = 1; k < r.milestones.size(); ++k) {
      if (r.milestones[k] == r.milestones[k - 1]) continue;
      EXPECT_EQ(r.milestones[k], r.milestones[k - 1] + 1);
      const Milestone& passed = map.milestones[static_cast<std::size_t>(r.milestones[k - 1])];
      const double destination_x = 0.02 * passed.last_image;
      EXPECT_GT(r.poses[k].x, destination_x - 0.02) << "milestone " << r.milestones[k - 1];
      EXPECT_LT(r.poses[k].x, destination_x + 0.09) << "milestone " << r.milestones[k - 1];
    }
  }
}

TEST(FunnelLaneRepeaterTest, RepeatStartedOffThePathConvergesTowardIt) {
  // 0.2 m to the left, heading 5° further away from the path. (The mirror image behaves
  // alike: 0.099 m at the end.)
  const CorridorScene scene;
  FunnelLaneRepeater repeater(TeachStraight(scene), FastRepeat());
  const LoopResult r = RunLoop(scene, &repeater, {0.0, 0.2, 5.0 * kDeg}, 400);
  ASSERT_EQ(r.last.status, RepeatStatus::kFinished);
  const double end_error = std::abs(r.poses.back().y);
  double worst = 0.0;
  for (const Pose2& p : r.poses) worst = std::max(worst, std::abs(p.y));
  std::printf("2D, started 0.2 m, 5 deg off: lateral error at the end %.3f m, worst %.3f m\n",
              end_error, worst);
  EXPECT_LT(end_error, 0.6 * 0.2);
  EXPECT_LT(worst, 0.25);
  EXPECT_NEAR(r.poses.back().x, 3.0, 0.15);
}

TEST(FunnelLaneRepeaterTest, OccludedFeaturesAreLostAndNotRecovered) {
  // The paper's experiment 1 for the 2D method: the robot stands still while a dark body
  // crosses the view; the features it covers are lost for the rest of the milestone.
  const CorridorScene scene;
  FunnelLaneOptions options = FastRepeat();
  options.lost_patience_frames = 100;
  FunnelLaneRepeater repeater(TeachStraight(scene, 41), options);
  const Pose2 stop{0.06, 0.0, 0.0};
  RepeatCommand before, after;
  for (int k = 0; k < 24; ++k) {
    cv::Mat image = scene.Render(CameraPose(stop));
    if (k >= 2 && k < 22) {
      testing::DrawOccluder(&image, {static_cast<float>(-60 + 40 * (k - 2)), 260.0f}, 90.0);
    }
    const RepeatCommand c = repeater.Update(image, 0.1 * k);
    repeater.SetExecutedSpeed(0.0);  // held still, as the runner's stop for crossings
    if (k == 1) before = c;
    after = c;
  }
  EXPECT_EQ(after.milestone, before.milestone);
  EXPECT_GT(after.features_lost - before.features_lost, 20);
  EXPECT_EQ(after.features_recovered, 0);
  EXPECT_LT(after.tracked, before.tracked - 20);
  std::printf("2D, occluder: tracked %d -> %d, lost %lld, recovered %lld\n", before.tracked,
              after.tracked, static_cast<long long>(after.features_lost - before.features_lost),
              static_cast<long long>(after.features_recovered));
}

TEST(FunnelLaneRepeaterTest, DistanceBoundPassesAMilestoneTheImagesCannotPlace) {
  // The camera sees the key image of milestone 0 however far the robot drives (as on
  // ground whose images do not show the approach): without the bound the milestone is
  // never passed; with it, once twice its taught baseline has been driven. A robot held
  // still drives nothing, however long.
  const CorridorScene scene;
  const TeachMap& map = TeachStraight(scene, 41);
  const double baseline = map.milestones[0].baseline_m;
  ASSERT_GT(baseline, 0.1);
  const cv::Mat stuck = scene.Render(CameraPose({}));
  const auto first_switch = [&](double overrun, bool held, RepeatCommand* at) {
    FunnelLaneOptions options = FastRepeat();
    options.max_milestone_overrun = overrun;
    options.lost_patience_frames = 1000;
    FunnelLaneRepeater repeater(map, options);
    for (int k = 0; k < 100; ++k) {
      *at = repeater.Update(stuck, 0.1 * k);
      if (held) repeater.SetExecutedSpeed(0.0);
      if (at->switched) return k;
    }
    return -1;
  };
  RepeatCommand at;
  EXPECT_EQ(first_switch(0.0, false, &at), -1);
  EXPECT_EQ(first_switch(2.0, true, &at), -1);
  const int k = first_switch(2.0, false, &at);
  // 0.2 m/s for 0.1 s per frame: passed at the first frame beyond 2 * baseline.
  EXPECT_EQ(k, static_cast<int>(std::floor(2.0 * baseline / 0.02 + 1e-9)) + 1);
  EXPECT_TRUE(at.switched_by_distance);
  EXPECT_EQ(at.milestone, 1);
  std::printf("2D, distance bound: baseline %.3f m, passed at frame %d\n", baseline, k);
}

TEST(FunnelLaneRepeaterTest, BlankImagesEndTheRepeatAsLostAfterThePatience) {
  const CorridorScene scene;
  FunnelLaneOptions options = FastRepeat();
  options.lost_patience_frames = 5;
  FunnelLaneRepeater repeater(TeachStraight(scene, 41), options);
  EXPECT_EQ(repeater.Update(scene.Render(CameraPose({})), 0.0).status, RepeatStatus::kDriving);
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(128));
  for (int k = 1; k <= 5; ++k) {
    const RepeatCommand c = repeater.Update(blank, 0.1 * k);
    EXPECT_EQ(c.status, RepeatStatus::kDriving) << k;
    EXPECT_TRUE(c.too_few_features);
    EXPECT_EQ(c.twist.yaw_rate_radps, 0.0);  // straight on while blind
  }
  RepeatCommand c = repeater.Update(blank, 0.6);
  EXPECT_EQ(c.status, RepeatStatus::kLost);
  EXPECT_EQ(c.twist.v_mps, 0.0);
  // Lost stays lost, even with good images again.
  c = repeater.Update(scene.Render(CameraPose({})), 0.7);
  EXPECT_EQ(c.status, RepeatStatus::kLost);
  EXPECT_STREQ(ToString(c.status), "lost");
}

TEST(FunnelLaneRepeaterTest, BadInputAndOptionsAreRejected) {
  const CorridorScene scene;
  const TeachMap& map = TeachStraight(scene, 41);
  FunnelLaneRepeater repeater(map);
  EXPECT_THROW(repeater.Update(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0)), 0.0),
               std::invalid_argument);
  repeater.Update(scene.Render(CameraPose({})), 1.0);
  EXPECT_THROW(repeater.Update(scene.Render(CameraPose({})), 0.5), std::invalid_argument);
  EXPECT_THROW(FunnelLaneRepeater(TeachMap{}), std::invalid_argument);
  FunnelLaneOptions o;
  o.start_milestone = 99;
  EXPECT_THROW(FunnelLaneRepeater(map, o), std::invalid_argument);
  // The field a repeater built with `bad` options names ("" if it was built).
  const auto rejected_field = [&map](const FunnelLaneOptions& bad) -> std::string {
    try {
      FunnelLaneRepeater repeater_with(map, bad);
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  o = {};
  o.min_net_vote = 1.0;
  EXPECT_EQ(rejected_field(o), "min_net_vote");
  o = {};
  o.max_milestone_overrun = 0.5;
  EXPECT_EQ(rejected_field(o), "max_milestone_overrun");
  o = {};
  o.tracker.pyramid_levels = 9;
  EXPECT_EQ(rejected_field(o), "tracker.pyramid_levels");
  EXPECT_THROW(MakeRepeater("4d", map, FunnelLaneOptions{}, Localizer3dOptions{}),
               std::invalid_argument);
  EXPECT_STREQ(MakeRepeater("2d", map, FunnelLaneOptions{}, Localizer3dOptions{})->method(), "2d");
}

}  // namespace
}  // namespace trackbed::teach_repeat
