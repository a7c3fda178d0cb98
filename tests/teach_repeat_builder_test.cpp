// Teaching: milestones cut at a fixed interval (2D, in images or odometry distance) and by
// the growth of the local reconstruction's reprojection error (3D), the accuracy of the
// KLT-tracked last positions and of the 3-D reconstruction against the synthetic scene's
// ground truth, and input/option validation.
#include "trackbed/teach_repeat/milestone_builder.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "teach_repeat_test_scene.h"
#include "trackbed/common/option_error.h"

namespace trackbed::teach_repeat {
namespace {

using geometry::Pose2;
using testing::CameraPose;
using testing::CorridorScene;
using testing::TestCamera;

constexpr double kDegTeach = M_PI / 180.0;

/// A gently curving teach route: 2 cm per image, yawing 0.15° per image after image 40.
Pose2 TeachPose(int k) {
  Pose2 p;
  for (int i = 0; i < k; ++i) {
    const double yaw_rate = i >= 40 ? 0.15 * M_PI / 180.0 : 0.0;
    p = geometry::Compose(p, {0.02, 0.0, yaw_rate});
  }
  return p;
}

TeachMap Teach(const CorridorScene& scene, const MilestoneBuilderOptions& options, int images,
               std::vector<TeachStep>* steps = nullptr) {
  MilestoneBuilder builder(TestCamera(), options);
  for (int k = 0; k < images; ++k) {
    const Pose2 pose = TeachPose(k);
    const TeachStep step = builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose);
    if (steps) steps->push_back(step);
  }
  return builder.Finish();
}

TEST(MilestoneBuilderTest, TwoDimensionalMilestonesAreCutAtAFixedImageInterval) {
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.interval_images = 10;
  const TeachMap map = Teach(scene, options, 56);
  ASSERT_EQ(map.milestones.size(), 6u);  // 0–10, …, 40–50, and 50–55 at the end
  EXPECT_EQ(map.mode, TeachMode::k2d);
  EXPECT_EQ(map.images.size(), 56u);
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    const Milestone& m = map.milestones[k];
    EXPECT_EQ(m.first_image, static_cast<int>(10 * k)) << k;
    EXPECT_EQ(m.last_image, k + 1 < map.milestones.size() ? static_cast<int>(10 * (k + 1)) : 55);
    EXPECT_EQ(m.cut,
              k + 1 < map.milestones.size() ? MilestoneCut::kInterval : MilestoneCut::kEndOfTeach);
    EXPECT_DOUBLE_EQ(m.first_t_s, 0.1 * m.first_image);
    EXPECT_FALSE(m.reconstructed);
    EXPECT_GT(m.features.size(), 80u) << k;
    EXPECT_EQ(m.key_image.size(), cv::Size(640, 480));
    for (const MilestoneFeature& f : m.features) {
      EXPECT_EQ(f.patch.rows, 11);
      EXPECT_EQ(f.patch.type(), CV_8UC1);
    }
  }
  // The odometry is kept as metadata.
  ASSERT_TRUE(map.images[20].odometry.has_value());
  EXPECT_NEAR(map.images[20].odometry->x, 0.4, 1e-12);
}

TEST(MilestoneBuilderTest, TwoDimensionalMilestonesCanBeCutByOdometryDistance) {
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.interval_unit = IntervalUnit::kDistance;
  options.interval_m = 0.25;  // 2 cm per image: 13 images (0.26 m) per milestone
  const TeachMap map = Teach(scene, options, 40);
  ASSERT_EQ(map.milestones.size(), 3u);  // image 39 closes the third; nothing follows
  EXPECT_EQ(map.milestones[0].last_image, 13);
  EXPECT_EQ(map.milestones[1].last_image, 26);
  EXPECT_EQ(map.milestones[2].last_image, 39);
  EXPECT_EQ(map.milestones[2].cut, MilestoneCut::kInterval);
  EXPECT_NEAR(map.milestones[0].baseline_m, 0.26, 1e-9);
  // Without odometry a distance interval cannot be measured.
  MilestoneBuilder builder(TestCamera(), options);
  EXPECT_THROW(builder.AddImage(scene.Render(CameraPose({})), 0.0), std::invalid_argument);
}

TEST(MilestoneBuilderTest, TrackedLastPositionsMatchTheSceneToASubPixel) {
  // The true last position of every feature: cast its first-image ray into the scene and
  // project the hit into the last camera.
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.interval_images = 15;
  const TeachMap map = Teach(scene, options, 16);
  ASSERT_EQ(map.milestones.size(), 1u);
  const Milestone& m = map.milestones[0];
  const Eigen::Isometry3d T_world_first = CameraPose(TeachPose(m.first_image));
  const Eigen::Isometry3d T_world_last = CameraPose(TeachPose(m.last_image));
  const geometry::PinholeCamera c = TestCamera();
  std::vector<double> errors;
  for (const MilestoneFeature& f : m.features) {
    const std::optional<Eigen::Vector3d> p = scene.RayCast(T_world_first, f.first_px);
    ASSERT_TRUE(p.has_value());
    const Eigen::Vector3d q = T_world_last.inverse() * *p;
    errors.push_back(std::hypot(c.fx * q.x() / q.z() + c.cx - f.last_px.x,
                                c.fy * q.y() / q.z() + c.cy - f.last_px.y));
  }
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  const double p90 = errors[errors.size() * 9 / 10];
  std::printf("KLT over 15 images: %zu features, median error %.3f px, 90th percentile %.3f px\n",
              errors.size(), median, p90);
  // KLT's window moves by translation only while the walls' perspective changes, so its
  // error grows by ~0.02 px per image (0.05 px after one image, no bias); a few corners
  // are occlusion T-junctions, not scene points.
  EXPECT_LT(median, 0.4);
  EXPECT_LT(p90, 1.0);
}

TEST(MilestoneBuilderTest, ThreeDimensionalMilestonesEndWhenTheReprojectionErrorGrows) {
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.mode = TeachMode::k3d;
  std::vector<TeachStep> steps;
  const TeachMap map = Teach(scene, options, 70, &steps);
  ASSERT_GE(map.milestones.size(), 3u);
  std::printf("3D teach, threshold %.2f px: %zu milestones over 70 images:",
              options.max_reprojection_error_px, map.milestones.size());
  for (const Milestone& m : map.milestones) {
    std::printf(" [%d–%d %.3f px]", m.first_image, m.last_image, m.reprojection_error_px);
  }
  std::printf("\n");
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    const Milestone& m = map.milestones[k];
    // The last milestone, cut by the end of the teach, is reconstructed only if it
    // reached the minimum baseline.
    EXPECT_EQ(m.reconstructed, m.baseline_m >= options.min_baseline_m) << k;
    if (k + 1 < map.milestones.size()) {
      EXPECT_TRUE(m.reconstructed) << k;
      EXPECT_EQ(m.cut, MilestoneCut::kReprojectionError) << k;
      // The milestone ends at the last image below the threshold; its successor image
      // (the next milestone's second) was above it.
      EXPECT_LE(m.reprojection_error_px, options.max_reprojection_error_px);
      const TeachStep& cut_step = steps[static_cast<std::size_t>(m.last_image + 1)];
      EXPECT_TRUE(cut_step.milestone_closed);
      EXPECT_EQ(map.milestones[k + 1].first_image, m.last_image);
      EXPECT_GE(m.baseline_m, options.min_baseline_m) << k;
    }
  }
  // A looser threshold gives longer milestones.
  MilestoneBuilderOptions loose = options;
  loose.max_reprojection_error_px = 0.2;
  const TeachMap longer = Teach(scene, loose, 70);
  EXPECT_LT(longer.milestones.size(), map.milestones.size());
}

TEST(MilestoneBuilderTest, ThreeDimensionalReconstructionIsMetricAndMatchesTheScene) {
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.mode = TeachMode::k3d;
  const TeachMap map = Teach(scene, options, 70);
  ASSERT_GE(map.milestones.size(), 2u);
  for (const Milestone& m : map.milestones) {
    if (!m.reconstructed) continue;  // a short last milestone
    const Eigen::Isometry3d T_world_first = CameraPose(TeachPose(m.first_image));
    const Eigen::Isometry3d truth = T_world_first.inverse() * CameraPose(TeachPose(m.last_image));
    // Metric translation (scaled by the odometry distance, exact here) and rotation.
    EXPECT_LT((m.T_first_last.translation() - truth.translation()).norm(),
              0.01 * m.baseline_m + 2e-3);
    const double rotation_deg =
        Eigen::AngleAxisd(m.T_first_last.linear().transpose() * truth.linear()).angle() * 180.0 /
        M_PI;
    EXPECT_LT(rotation_deg, 0.1);
    // 3-D points against the scene: within 5 % of their depth for most features.
    int good = 0;
    for (const MilestoneFeature& f : m.features) {
      const std::optional<Eigen::Vector3d> p = scene.RayCast(T_world_first, f.first_px);
      ASSERT_TRUE(p.has_value());
      const Eigen::Vector3d p_first = T_world_first.inverse() * *p;
      if ((f.p_first - p_first).norm() < 0.05 * p_first.z()) ++good;
    }
    EXPECT_GT(good, static_cast<int>(0.85 * m.features.size()))
        << "milestone " << m.first_image << "–" << m.last_image;
  }
}

TEST(MilestoneBuilderTest, ATurnInPlaceGivesMilestonesWithoutReconstruction) {
  // No translation, no baseline: the essential matrix would be ill-conditioned.
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.mode = TeachMode::k3d;
  options.max_milestone_images = 10;
  MilestoneBuilder builder(TestCamera(), options);
  for (int k = 0; k <= 20; ++k) {
    const Pose2 pose{0.5, 0.0, 0.5 * kDegTeach * k};
    builder.AddImage(scene.Render(CameraPose(pose)), 0.1 * k, pose);
  }
  const TeachMap map = builder.Finish();
  ASSERT_EQ(map.milestones.size(), 2u);
  for (const Milestone& m : map.milestones) {
    EXPECT_FALSE(m.reconstructed);
    EXPECT_EQ(m.cut, MilestoneCut::kMaxImages);
    EXPECT_EQ(m.baseline_m, 0.0);
    EXPECT_GT(m.features.size(), 50u);
  }
}

TEST(MilestoneBuilderTest, ThreeDimensionalTeachingNeedsOdometry) {
  const CorridorScene scene;
  MilestoneBuilderOptions options;
  options.mode = TeachMode::k3d;
  MilestoneBuilder builder(TestCamera(), options);
  EXPECT_THROW(builder.AddImage(scene.Render(CameraPose({})), 0.0), std::invalid_argument);
}

TEST(MilestoneBuilderTest, BadInputIsRejectedAndLeavesTheBuilderUnchanged) {
  const CorridorScene scene;
  MilestoneBuilder builder(TestCamera());
  EXPECT_THROW(builder.AddImage(cv::Mat(240, 320, CV_8UC1, cv::Scalar(0)), 0.0),
               std::invalid_argument);
  EXPECT_THROW(builder.AddImage(cv::Mat(480, 640, CV_8UC3, cv::Scalar(0)), 0.0),
               std::invalid_argument);
  builder.AddImage(scene.Render(CameraPose({})), 1.0);
  EXPECT_THROW(builder.AddImage(scene.Render(CameraPose({})), 0.5), std::invalid_argument);
  builder.AddImage(scene.Render(CameraPose({0.02, 0.0, 0.0})), 1.1);
  const TeachMap map = builder.Finish();
  EXPECT_EQ(map.images.size(), 2u);
  ASSERT_EQ(map.milestones.size(), 1u);
  EXPECT_EQ(map.milestones[0].cut, MilestoneCut::kEndOfTeach);
}

TEST(MilestoneBuilderTest, OptionErrorsNameTheField) {
  auto field_of = [](const MilestoneBuilderOptions& o) -> std::string {
    try {
      o.Validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  MilestoneBuilderOptions o;
  EXPECT_EQ(field_of(o), "");
  o.interval_images = 0;
  EXPECT_EQ(field_of(o), "interval_images");
  o = {};
  o.max_reprojection_error_px = 0.0;
  EXPECT_EQ(field_of(o), "max_reprojection_error_px");
  o = {};
  o.patch_size_px = 10;
  EXPECT_EQ(field_of(o), "patch_size_px");
  o = {};
  o.tracker.window_px = 4;
  EXPECT_EQ(field_of(o), "tracker.window_px");
  o = {};
  o.two_view.min_inliers = 4;
  EXPECT_EQ(field_of(o), "two_view.min_inliers");
  geometry::PinholeCamera bad = TestCamera();
  bad.fx = -1.0;
  try {
    MilestoneBuilder builder(bad);
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "camera.fx");
  }
}

}  // namespace
}  // namespace trackbed::teach_repeat
