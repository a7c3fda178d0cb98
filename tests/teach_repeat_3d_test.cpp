// Repeat 3D (Diosi et al. 2007): two-view geometry (essential matrix, triangulation, the
// scale ratio) on exact and noisy correspondences, patch matching, path offsets and the
// steering law; then the localizer on synthetic images — its pose against ground truth,
// features occluded by a passing body recovered by patch matching, and a closed kinematic
// loop started 0.2 m and 5° off the taught path.
#include "trackbed/teach_repeat/milestone_localizer_3d.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "teach_repeat_test_scene.h"
#include "trackbed/common/option_error.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/teach_repeat/funnel_lane_controller.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/teach_repeat_geometry.h"

namespace trackbed::teach_repeat {
namespace {

using geometry::Pose2;
using navigation::IntegrateTwist;  // the robot of these tests drives the twist exactly
using testing::CameraPose;
using testing::CorridorScene;
using testing::TestCamera;

constexpr double kDeg = M_PI / 180.0;

double AngleDeg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return Eigen::AngleAxisd(A.transpose() * B).angle() / kDeg;
}

Eigen::Isometry3d Pose(const Eigen::Vector3d& axis_angle, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (axis_angle.norm() > 0.0) {
    T.linear() = Eigen::AngleAxisd(axis_angle.norm(), axis_angle.normalized()).toRotationMatrix();
  }
  T.translation() = t;
  return T;
}

// ---------------------------------------------------------------------------------------
// Two-view geometry.

struct Correspondences {
  std::vector<Eigen::Vector3d> p_a;  // true points in camera a
  std::vector<cv::Point2f> a, b;
};

/// Points 1.5–8 m in front of camera a, seen by a and by b = T_a_b (p_a = T_a_b · p_b),
/// with Gaussian pixel noise σ.
Correspondences MakeCorrespondences(const Eigen::Isometry3d& T_a_b, int n, double sigma,
                                    std::mt19937_64& rng) {
  const geometry::PinholeCamera c = TestCamera();
  std::uniform_real_distribution<double> u(20.0, 620.0), v(20.0, 460.0), z(1.5, 8.0);
  std::normal_distribution<double> noise(0.0, sigma);
  Correspondences s;
  const Eigen::Isometry3d T_b_a = T_a_b.inverse();
  while (static_cast<int>(s.a.size()) < n) {
    const double Z = z(rng);
    const Eigen::Vector3d p((u(rng) - c.cx) * Z / c.fx, (v(rng) - c.cy) * Z / c.fy, Z);
    const std::optional<cv::Point2d> qa = ProjectPoint(c, p);
    const std::optional<cv::Point2d> qb = ProjectPoint(c, T_b_a * p);
    if (!qa || !qb || qb->x < 0 || qb->x > 639 || qb->y < 0 || qb->y > 479) continue;
    s.p_a.push_back(p);
    s.a.emplace_back(static_cast<float>(qa->x + noise(rng)),
                     static_cast<float>(qa->y + noise(rng)));
    s.b.emplace_back(static_cast<float>(qb->x + noise(rng)),
                     static_cast<float>(qb->y + noise(rng)));
  }
  return s;
}

TEST(TwoViewGeometryTest, RelativePoseAndStructureAreRecoveredAtTheGivenScale) {
  std::mt19937_64 rng(3);
  // The robot moved 0.3 m forward, 4 cm to the right and yawed 3° (and a little pitch).
  const Eigen::Isometry3d truth = Pose({0.2 * kDeg, -3.0 * kDeg, 0.0}, {0.04, 0.002, 0.3});
  const Correspondences s = MakeCorrespondences(truth, 150, 0.2, rng);
  const TwoViewGeometry g =
      ReconstructTwoView(TestCamera(), s.a, s.b, truth.translation().norm(), TwoViewOptions{});
  ASSERT_TRUE(g.ok) << g.reason;
  EXPECT_GT(g.inliers, 140);
  EXPECT_LT(AngleDeg(g.T_a_b.linear(), truth.linear()), 0.05);
  const double direction_deg =
      std::acos(std::clamp(g.T_a_b.translation().normalized().dot(truth.translation().normalized()),
                           -1.0, 1.0)) /
      kDeg;
  EXPECT_LT(direction_deg, 1.0);
  EXPECT_NEAR(g.T_a_b.translation().norm(), truth.translation().norm(), 1e-12);
  EXPECT_LT(g.reprojection_error_px, 0.3);
  EXPECT_GT(g.median_parallax_px, 10.0);
  // Structure: within 5 % of depth for most points (those near the focus of expansion,
  // straight ahead, see almost no parallax and triangulate poorly).
  int good = 0;
  for (std::size_t i = 0; i < s.p_a.size(); ++i) {
    if (g.inlier[i] && (g.p_a[i] - s.p_a[i]).norm() < 0.05 * s.p_a[i].z()) ++good;
  }
  EXPECT_GT(good, 110);
  std::printf("two-view: rotation %.4f deg, direction %.3f deg, reprojection %.3f px\n",
              AngleDeg(g.T_a_b.linear(), truth.linear()), direction_deg, g.reprojection_error_px);
}

TEST(TwoViewGeometryTest, OutliersAreRejectedAndExactDataFitsExactly) {
  std::mt19937_64 rng(4);
  const Eigen::Isometry3d truth = Pose({0.0, 2.0 * kDeg, 0.0}, {-0.05, 0.0, 0.25});
  Correspondences s = MakeCorrespondences(truth, 100, 0.0, rng);
  std::uniform_real_distribution<float> u(0.0f, 600.0f);
  for (int i = 0; i < 30; ++i) s.b[static_cast<std::size_t>(i)] = {u(rng), u(rng)};
  const TwoViewGeometry g = ReconstructTwoView(TestCamera(), s.a, s.b, 1.0, TwoViewOptions{});
  ASSERT_TRUE(g.ok);
  int outliers_kept = 0;
  for (int i = 0; i < 30; ++i) outliers_kept += g.inlier[static_cast<std::size_t>(i)];
  EXPECT_LE(outliers_kept, 2);  // a random point may happen to lie near its epipolar line
  EXPECT_GE(g.inliers, 68);
  EXPECT_LT(AngleDeg(g.T_a_b.linear(), truth.linear()), 1e-3);
  EXPECT_LT(g.reprojection_error_px, 1e-2);
}

TEST(TwoViewGeometryTest, ScaleRatioMakesAUnitReconstructionMetric) {
  // The milestone's points (metric, from teaching) and a repeat's reconstruction at unit
  // baseline differ by the baseline: ScaleRatio recovers it (Choi & Ha §III).
  std::mt19937_64 rng(5);
  const Eigen::Isometry3d truth = Pose({0.0, 1.0 * kDeg, 0.0}, {0.03, 0.0, 0.18});
  const Correspondences s = MakeCorrespondences(truth, 120, 0.15, rng);
  const TwoViewGeometry unit = ReconstructTwoView(TestCamera(), s.a, s.b, -1.0, TwoViewOptions{});
  ASSERT_TRUE(unit.ok);
  EXPECT_NEAR(unit.T_a_b.translation().norm(), 1.0, 1e-12);
  const std::optional<double> ratio = ScaleRatio(s.p_a, unit.p_a, unit.inlier);
  ASSERT_TRUE(ratio.has_value());
  EXPECT_NEAR(*ratio, truth.translation().norm(), 0.01 * truth.translation().norm());
  // The metric translation follows.
  EXPECT_LT((unit.T_a_b.translation() * *ratio - truth.translation()).norm(), 0.005);
  // Degenerate inputs.
  EXPECT_FALSE(ScaleRatio({}, {}).has_value());
  EXPECT_FALSE(ScaleRatio({Eigen::Vector3d::Zero()}, {Eigen::Vector3d::UnitZ()}).has_value());
  EXPECT_THROW(ScaleRatio({Eigen::Vector3d::UnitZ()}, {}), std::invalid_argument);
}

TEST(TwoViewGeometryTest, TooFewCorrespondencesAreAFailureNotAnException) {
  std::vector<cv::Point2f> a(4, {100.0f, 100.0f});
  const TwoViewGeometry g = ReconstructTwoView(TestCamera(), a, a, 1.0, TwoViewOptions{});
  EXPECT_FALSE(g.ok);
  EXPECT_NE(g.reason.find("too few"), std::string::npos);
  EXPECT_THROW(ReconstructTwoView(TestCamera(), a, {}, 1.0, TwoViewOptions{}),
               std::invalid_argument);
}

TEST(TwoViewGeometryTest, LinearTriangulationIsExactOnExactRays) {
  const Eigen::Isometry3d T_b_a = Pose({0.01, -0.05, 0.02}, {-0.2, 0.01, -0.3});
  const Eigen::Vector3d p(0.4, -0.3, 3.5);
  const Eigen::Vector3d q = T_b_a * p;
  const Eigen::Vector3d back = TriangulateLinear(p.head<2>() / p.z(), q.head<2>() / q.z(), T_b_a);
  EXPECT_LT((back - p).norm(), 1e-9);
}

// ---------------------------------------------------------------------------------------
// Patches, image shift, path offsets, steering.

TEST(PatchMatchTest, ZnccFindsAShiftedPatchToASubPixel) {
  const CorridorScene scene;
  const cv::Mat image = scene.Render(CameraPose({}));
  const cv::Point2f feature(250.3f, 200.6f);
  cv::Mat patch;
  cv::getRectSubPix(image, cv::Size(11, 11), feature, patch, CV_8U);
  // The image moved by (3.4, −2.2) px.
  const cv::Mat M = (cv::Mat_<double>(2, 3) << 1.0, 0.0, 3.4, 0.0, 1.0, -2.2);
  cv::Mat moved;
  cv::warpAffine(image, moved, M, image.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  const PatchMatch m = SearchPatch(moved, patch, feature, 5, 2.0);
  ASSERT_TRUE(m.found);
  EXPECT_GT(m.score, 0.9);  // bilinear resampling of sharp edges costs a few per cent
  EXPECT_NEAR(m.position.x, feature.x + 3.4f, 0.3);
  EXPECT_NEAR(m.position.y, feature.y - 2.2f, 0.3);
  // Gain and offset do not matter.
  cv::Mat brighter;
  moved.convertTo(brighter, CV_8U, 0.7, 40.0);
  EXPECT_GT(SearchPatch(brighter, patch, feature, 5, 2.0).score, 0.9);
  // A flat window matches nothing; a window outside the image is not compared.
  const cv::Mat flat(480, 640, CV_8UC1, cv::Scalar(90));
  EXPECT_EQ(*Zncc(patch, flat, {100, 100}, 2.0), 0.0);
  EXPECT_FALSE(Zncc(patch, image, {2, 100}, 2.0).has_value());
  EXPECT_FALSE(SearchPatch(image, patch, {-50.0f, -50.0f}, 3, 2.0).found);
}

TEST(PatchMatchTest, PhaseCorrelationFindsTheGlobalShift) {
  const CorridorScene scene;
  const cv::Mat a = scene.Render(CameraPose({}));
  const cv::Mat b = scene.Render(CameraPose({0.0, 0.0, 4.0 * kDeg}));  // a yaw to the left
  const cv::Point2f shift = EstimateImageShift(a, b);
  // Turning left moves the image right by about fx·tan(4°) = 26.7 px.
  EXPECT_NEAR(shift.x, TestCamera().fx * std::tan(4.0 * kDeg), 3.0);
  EXPECT_NEAR(shift.y, 0.0, 1.0);
}

TEST(PathOffsetTest, HandMadeOffsetsHaveTheRightSigns) {
  // A taught segment 0.4 m straight ahead (camera z).
  const Eigen::Isometry3d T_first_last = Pose({0, 0, 0}, {0.0, 0.0, 0.4});
  // 0.1 m left (camera −x), a quarter of the way, turned 3° left (about camera −y).
  const Eigen::Isometry3d T_first_cam = Pose({0.0, -3.0 * kDeg, 0.0}, {-0.1, 0.0, 0.1});
  const PathOffset o = ComputePathOffset(T_first_cam, T_first_last);
  EXPECT_NEAR(o.lateral_m, 0.1, 1e-12);
  EXPECT_NEAR(o.heading_rad, 3.0 * kDeg, 1e-12);
  EXPECT_NEAR(o.progress, 0.25, 1e-12);
  EXPECT_NEAR(o.segment_length_m, 0.4, 1e-12);
  // Right of the path, turned right.
  const PathOffset r =
      ComputePathOffset(Pose({0.0, 2.0 * kDeg, 0.0}, {0.05, 0.0, 0.5}), T_first_last);
  EXPECT_NEAR(r.lateral_m, -0.05, 1e-12);
  EXPECT_NEAR(r.heading_rad, -2.0 * kDeg, 1e-12);
  EXPECT_NEAR(r.progress, 1.25, 1e-12);
  // On a curved segment (the last camera turned 10° left) the reference heading follows
  // the progress: half-way, 5°.
  const Eigen::Isometry3d curved = Pose({0.0, -10.0 * kDeg, 0.0}, {-0.03, 0.0, 0.4});
  const Eigen::Isometry3d mid = Pose({0.0, -5.0 * kDeg, 0.0}, curved.translation() / 2.0);
  EXPECT_NEAR(ComputePathOffset(mid, curved).heading_rad, 0.0, 1e-9);
  EXPECT_NEAR(ComputePathOffset(mid, curved).lateral_m, 0.0, 1e-9);
}

TEST(PathFollowingTest, SteersBackTowardThePathAndSaturates) {
  // Left of the path or turned left: turn right (negative yaw rate), and vice versa.
  EXPECT_LT(PathFollowingYawRate(0.1, 0.0, 0.1, 1.0, 1.0), 0.0);
  EXPECT_LT(PathFollowingYawRate(0.0, 0.05, 0.1, 1.0, 1.0), 0.0);
  EXPECT_GT(PathFollowingYawRate(-0.1, 0.0, 0.1, 1.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(PathFollowingYawRate(0.0, 0.0, 0.1, 1.0, 1.0), 0.0);
  // ω = −v (y/L² + 2θ/L).
  EXPECT_NEAR(PathFollowingYawRate(0.1, 0.02, 0.2, 0.5, 1.0), -0.2 * (0.1 / 0.25 + 0.04 / 0.5),
              1e-12);
  EXPECT_DOUBLE_EQ(PathFollowingYawRate(5.0, 0.0, 0.2, 0.5, 0.07), -0.07);
  // On the taught path of a curve κ the law turns at the path's own rate v·κ.
  EXPECT_NEAR(PathFollowingYawRate(0.0, 0.0, 0.05, 1.0, 1.0, 1.0 / 1.5), 0.05 / 1.5, 1e-12);
  // Closed loop on the kinematics: a critically damped approach over ~L (4 m = 8 L
  // leave (0.2 + 0.2·8)·e⁻⁸ = 0.6 mm), no overshoot to speak of.
  Pose2 p{0.0, 0.2, 0.0};
  double most_negative = 0.0;
  for (int k = 0; k < 800; ++k) {
    const double omega = PathFollowingYawRate(p.y, p.yaw, 0.1, 0.5, 1.0);
    p = IntegrateTwist(p, {0.1, omega}, 0.05);
    most_negative = std::min(most_negative, p.y);
  }
  EXPECT_LT(std::abs(p.y), 0.002);
  EXPECT_GT(most_negative, -0.01);
}

// ---------------------------------------------------------------------------------------
// The localizer on synthetic images.

/// A 3D teach along the corridor's axis, 2 cm per image (`images` images: 151 for 3 m);
/// taught once per length and shared by the tests.
const TeachMap& TeachStraight3d(const CorridorScene& scene, int images = 151) {
  static std::map<int, TeachMap> cache;
  auto it = cache.find(images);
  if (it == cache.end()) {
    MilestoneBuilderOptions options;
    options.mode = TeachMode::k3d;
    MilestoneBuilder builder(TestCamera(), options);
    for (int k = 0; k < images; ++k) {
      const Pose2 pose{0.02 * k, 0.0, 0.0};
      builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose);
    }
    it = cache.emplace(images, builder.Finish()).first;
  }
  return it->second;
}

Localizer3dOptions FastRepeat() {
  Localizer3dOptions o;
  o.forward_speed_mps = 0.2;
  o.max_yaw_rate_radps = 10.0 * kDeg;
  return o;
}

TEST(MilestoneLocalizer3dTest, PoseRelativeToTheMilestoneMatchesGroundTruth) {
  // Open loop: the robot drives 0.1 m left of the taught path, turned 2° left; the
  // localizer's pose in each milestone's first camera frame is compared with the truth.
  const CorridorScene scene;
  const TeachMap& map = TeachStraight3d(scene, 71);
  MilestoneLocalizer3d localizer(map, FastRepeat());
  double worst_m = 0.0, worst_deg = 0.0, worst_lateral = 0.0;
  int essential = 0, frames = 0;
  for (int k = 0; k < 60; ++k) {
    const Pose2 pose{0.02 * k, 0.1, 2.0 * kDeg};
    const RepeatCommand c = localizer.Update(scene.Render(CameraPose(pose)), 0.1 * k);
    ASSERT_EQ(c.status, RepeatStatus::kDriving);
    ASSERT_TRUE(c.pose_valid) << "frame " << k;
    const Milestone& m = map.milestones[static_cast<std::size_t>(c.milestone)];
    const Eigen::Isometry3d truth =
        CameraPose({0.02 * m.first_image, 0.0, 0.0}).inverse() * CameraPose(pose);
    worst_m = std::max(worst_m, (c.T_first_cam.translation() - truth.translation()).norm());
    worst_deg = std::max(worst_deg, AngleDeg(c.T_first_cam.linear(), truth.linear()));
    // The camera sits 0.2 m ahead of the body: 0.1 + 0.2·sin 2° left of the path.
    worst_lateral =
        std::max(worst_lateral, std::abs(c.lateral_offset_m - (0.1 + 0.2 * std::sin(2.0 * kDeg))));
    EXPECT_NEAR(c.heading_error_rad, 2.0 * kDeg, 0.3 * kDeg) << "frame " << k;
    EXPECT_LT(c.twist.yaw_rate_radps, 0.0);  // steer back: right
    essential += c.essential_used ? 1 : 0;
    ++frames;
  }
  std::printf(
      "3D pose over %d frames: worst %.1f mm, %.3f deg, lateral %.1f mm; essential "
      "matrix used in %d\n",
      frames, 1e3 * worst_m, worst_deg, 1e3 * worst_lateral, essential);
  EXPECT_LT(worst_m, 0.02);
  EXPECT_LT(worst_deg, 0.3);
  EXPECT_LT(worst_lateral, 0.015);
  EXPECT_GT(essential, frames / 2);
}

TEST(MilestoneLocalizer3dTest, OccludedFeaturesAreRecoveredByPatchMatching) {
  // Choi & Ha's experiment 1: the robot stops, a body crosses the view (a dark disc
  // sweeping the image), the features it covers are lost; once it has passed, they are
  // found again at their reprojected positions by their stored patches.
  const CorridorScene scene;
  const TeachMap& map = TeachStraight3d(scene, 71);
  Localizer3dOptions options = FastRepeat();
  options.lost_patience_frames = 100;
  MilestoneLocalizer3d localizer(map, options);
  RepeatCommand before, during, after;
  int k = 0;
  auto frame = [&](const Pose2& pose, std::optional<cv::Point2f> occluder) {
    cv::Mat image = scene.Render(CameraPose(pose));
    if (occluder) testing::DrawOccluder(&image, *occluder, 90.0);
    const RepeatCommand c = localizer.Update(image, 0.1 * k++);
    return c;
  };
  for (int i = 0; i < 5; ++i) before = frame({0.02 * i, 0.0, 0.0}, std::nullopt);
  const Pose2 stop{0.08, 0.0, 0.0};
  int fewest_tracked = before.tracked;
  for (int i = 0; i < 20; ++i) {
    during = frame(stop, cv::Point2f(static_cast<float>(-60 + 40 * i), 260.0f));
    fewest_tracked = std::min(fewest_tracked, during.tracked);
  }
  for (int i = 0; i < 3; ++i) after = frame(stop, std::nullopt);
  ASSERT_EQ(after.milestone, before.milestone);
  const std::int64_t lost = after.features_lost - before.features_lost;
  const std::int64_t recovered = after.features_recovered - before.features_recovered;
  const double rate = static_cast<double>(recovered) / static_cast<double>(lost);
  std::printf(
      "3D, occluder: tracked %d -> %d (fewest) -> %d; lost %lld, recovered %lld (%.1f %%)\n",
      before.tracked, fewest_tracked, after.tracked, static_cast<long long>(lost),
      static_cast<long long>(recovered), 100.0 * rate);
  EXPECT_GT(lost, 30);
  EXPECT_GT(rate, 0.8);
  EXPECT_GT(after.tracked, before.tracked - 15);
  EXPECT_TRUE(after.pose_valid);
  // The recovered features sit at their reprojections.
  const std::vector<bool> tracked = localizer.tracked_mask();
  EXPECT_EQ(localizer.predicted().size(), tracked.size());
}

TEST(MilestoneLocalizer3dTest, RepeatStartedOffThePathConvergesTowardIt) {
  const CorridorScene scene;
  const TeachMap& map = TeachStraight3d(scene);
  MilestoneLocalizer3d localizer(map, FastRepeat());
  Pose2 pose{0.0, 0.2, 5.0 * kDeg};
  RepeatCommand c;
  double worst = 0.0;
  int frames = 0;
  for (; frames < 400; ++frames) {
    c = localizer.Update(scene.Render(CameraPose(pose)), 0.1 * frames);
    if (c.status != RepeatStatus::kDriving) break;
    worst = std::max(worst, std::abs(pose.y));
    pose = IntegrateTwist(pose, c.twist, 0.1);
  }
  std::printf(
      "3D, started 0.2 m, 5 deg off: lateral error at the end %.3f m, worst %.3f m, "
      "%lld features lost, %lld recovered\n",
      std::abs(pose.y), worst, static_cast<long long>(c.features_lost),
      static_cast<long long>(c.features_recovered));
  ASSERT_EQ(c.status, RepeatStatus::kFinished);
  EXPECT_LT(std::abs(pose.y), 0.1);
  EXPECT_LT(worst, 0.25);
  EXPECT_NEAR(pose.x, 3.0, 0.1);
}

TEST(MilestoneLocalizer3dTest, SeveralShortMilestonesArePassedInOneFrame) {
  // Milestones of 4 images (6 cm) and a repeat that moves 15 cm per frame, as in a
  // curve where the teach cut milestones of one to three images: the localizer must
  // pass two or three of them per frame to stay with the robot.
  const CorridorScene scene;
  MilestoneBuilderOptions teach;
  teach.mode = TeachMode::k3d;
  teach.max_milestone_images = 4;
  MilestoneBuilder builder(TestCamera(), teach);
  for (int k = 0; k < 121; ++k) {
    const Pose2 pose{0.02 * k, 0.0, 0.0};
    builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose);
  }
  const TeachMap map = builder.Finish();
  ASSERT_GE(map.milestones.size(), 30u);
  const auto behind_at_the_end = [&](int max_switches) {
    Localizer3dOptions o = FastRepeat();
    o.max_switches_per_frame = max_switches;
    MilestoneLocalizer3d localizer(map, o);
    int behind = 0;
    for (int k = 0; k < 12; ++k) {
      const double x = 0.15 * k;
      const RepeatCommand c = localizer.Update(scene.Render(CameraPose({x, 0.0, 0.0})), 0.1 * k);
      if (c.status != RepeatStatus::kDriving) break;
      // The milestone the robot is in: the last whose first image is at or before x.
      int truth = 0;
      for (std::size_t m = 0; m < map.milestones.size(); ++m) {
        if (0.02 * map.milestones[m].first_image <= x + 1e-9) truth = static_cast<int>(m);
      }
      behind = truth - c.milestone;
    }
    return behind;
  };
  EXPECT_LE(behind_at_the_end(3), 1);
  EXPECT_GE(behind_at_the_end(1), 5);  // once per frame falls ever further behind
}

TEST(MilestoneLocalizer3dTest, AMilestoneWithoutReconstructionIsFollowedByTheFunnelLane) {
  const CorridorScene scene;
  TeachMap map = TeachStraight3d(scene, 71);
  ASSERT_GE(map.milestones.size(), 5u);
  map.milestones[2].reconstructed = false;
  MilestoneLocalizer3d localizer(map, FastRepeat());
  Pose2 pose;
  RepeatCommand c;
  int fallback_frames = 0, last_milestone = 0;
  double worst = 0.0;
  for (int k = 0; k < 150; ++k) {
    c = localizer.Update(scene.Render(CameraPose(pose)), 0.1 * k);
    if (c.status != RepeatStatus::kDriving) break;
    EXPECT_GE(c.milestone, last_milestone);
    EXPECT_LE(c.milestone, last_milestone + 1);
    last_milestone = c.milestone;
    EXPECT_EQ(c.fallback_2d, c.milestone == 2) << "frame " << k;
    fallback_frames += c.fallback_2d ? 1 : 0;
    worst = std::max(worst, std::abs(pose.y));
    pose = IntegrateTwist(pose, c.twist, 0.1);
  }
  EXPECT_EQ(c.status, RepeatStatus::kFinished);
  EXPECT_GT(fallback_frames, 5);
  EXPECT_LT(worst, 0.03);
}

TEST(MilestoneLocalizer3dTest, TheSameImagesGiveTheSameCommands) {
  const CorridorScene scene;
  const TeachMap& map = TeachStraight3d(scene, 71);
  MilestoneLocalizer3d first(map, FastRepeat()), second(map, FastRepeat());
  for (int k = 0; k < 25; ++k) {
    const cv::Mat image = scene.Render(CameraPose({0.02 * k, 0.05, -1.0 * kDeg}));
    const RepeatCommand a = first.Update(image, 0.1 * k);
    const RepeatCommand b = second.Update(image, 0.1 * k);
    EXPECT_EQ(a.twist.yaw_rate_radps, b.twist.yaw_rate_radps) << k;
    EXPECT_EQ(a.milestone, b.milestone);
    EXPECT_EQ(a.tracked, b.tracked);
    EXPECT_TRUE(a.T_first_cam.matrix() == b.T_first_cam.matrix()) << k;
  }
}

TEST(MilestoneLocalizer3dTest, OptionErrorsNameTheField) {
  auto field_of = [](const Localizer3dOptions& o) -> std::string {
    try {
      o.Validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  Localizer3dOptions o;
  EXPECT_EQ(field_of(o), "");
  o.convergence_distance_m = 0.0;
  EXPECT_EQ(field_of(o), "convergence_distance_m");
  o = {};
  o.min_zncc = 1.5;
  EXPECT_EQ(field_of(o), "min_zncc");
  o = {};
  o.switch_progress = 0.0;
  EXPECT_EQ(field_of(o), "switch_progress");
  o = {};
  o.two_view.confidence = 1.0;
  EXPECT_EQ(field_of(o), "two_view.confidence");
  EXPECT_THROW(MilestoneLocalizer3d(TeachMap{}), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::teach_repeat
