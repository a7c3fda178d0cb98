// The KITTI twin (scenes/kitti_twin.yaml, docs/localization.md) at highway speed: its
// images exported in KITTI's layout carry a calibration-made scale bias into visual
// odometry, and estimating the rig's disparity offset removes it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/estimation/trajectory_metrics.h"
#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/perception/stereo_rectifier.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

// VO over `sequence`: the median ratio of its to the true length of each frame's motion,
// and its disparity offset estimate after the last frame (0 unless estimated).
struct VoScale {
  double length_ratio = 0.0;
  double offset_px = 0.0;
};

VoScale MeasureVoScale(const perception::KittiSequence& sequence, bool estimate_offset) {
  estimation::StereoVisualOdometryOptions options;
  options.estimate_disparity_offset = estimate_offset;
  estimation::StereoVisualOdometry vo(sequence.calibration(), options);
  estimation::Trajectory est, gt;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    const double t = sequence.times_s()[k];
    est.push_back({t, vo.Process(sequence.LoadLeft(k), sequence.LoadRight(k), t).T_world_cam});
    gt.push_back({t, sequence.poses()[k]});
  }
  return {estimation::FrameToFrameError(gt, est).length_ratio.median, vo.disparity_offset_px()};
}

// The offset VO should find: the cameras as built (`truth`) take the images, the given
// calibration rectifies them, and a point at infinity on the rectified left camera's
// axis then shows a disparity that is the rectification's error; the offset is what,
// added to it, gives the point's true disparity, 0. Ideal pinhole lenses.
double TrueDisparityOffsetPx(const calibration::StereoCalibration& truth,
                             const calibration::StereoCalibration& given) {
  const perception::StereoRectifier rectifier(given);
  const geometry::PinholeCamera& rectified = rectifier.camera().left;
  // Both rectified cameras have the rectified left camera's orientation.
  const Eigen::Matrix3d R_body_rect = rectifier.T_body_left().linear();
  const Eigen::Vector3d direction_body = R_body_rect * Eigen::Vector3d::UnitZ();
  // The column at which one camera's image of the point lands after rectification.
  const auto rectified_column = [&](const calibration::CameraIntrinsics& k_true,
                                    const Eigen::Isometry3d& T_body_true,
                                    const calibration::CameraIntrinsics& k_given,
                                    const Eigen::Isometry3d& T_body_given) {
    const Eigen::Vector3d c = T_body_true.linear().transpose() * direction_body;
    const double u = k_true.fx * c.x() / c.z() + k_true.cx;
    const double v = k_true.fy * c.y() / c.z() + k_true.cy;
    const Eigen::Vector3d ray((u - k_given.cx) / k_given.fx, (v - k_given.cy) / k_given.fy, 1.0);
    const Eigen::Vector3d r = R_body_rect.transpose() * T_body_given.linear() * ray;
    return rectified.fx * r.x() / r.z() + rectified.cx;
  };
  return rectified_column(truth.right, truth.T_body_right, given.right, given.T_body_right) -
         rectified_column(truth.left, truth.T_body_left, given.left, given.T_body_left);
}

TEST(KittiTwinTest, AtHighwaySpeedTheCalibrationsDisparityOffsetIsFoundAndTheScaleBiasGoes) {
  // 100 m at 25 m/s (40 frames) through seeds 1-5's cameras as built and calibrated
  // under `typical`: each given calibration's principal points and relative rotation
  // offset the rectified disparities, by 0.001 to 1.3 px on the rectified axis.
  //
  // What one seed can show (docs/results/2026-12-07-ground-sampling.md, "The highway
  // test over seeds"): at 25 m/s the scale rests on far points (4 px of disparity at
  // 100 m), where 0.04 px of offset is 1 % of scale. With the offset estimated, the
  // per-frame median over seeds 1-10 spreads 0.977-1.033 (0.955-1.030 with the images
  // of fcd6bc3's renderer), and 0.991-1.014 under `ideal`, with no offset to find: the
  // estimate's own wander (docs/localization.md). A bound of 1 % on one seed's median
  // failed 7 of those 10 seeds with fcd6bc3's images, 8 of 10 with these.
  // What holds at every seed is the offset found: within 0.24 px of the true one
  // (0.37 px with fcd6bc3's images), where the offset itself varies by 0.9 px or more
  // over the image (seeds 1-5); the bound, 0.4 px, is under half that. And where the
  // offset is more than 0.3 px, the scale bias shrinks at every seed, and by more
  // than half on the mean: 7.4 % as measured, 2.0 % with the offset estimated (7.2 and
  // 2.2 % with fcd6bc3's images).
  double measured_bias = 0.0, corrected_bias = 0.0;  // summed over seeds with an offset
  int with_offset = 0;
  for (int seed = 1; seed <= 5; ++seed) {
    const scenario::Scenario s =
        scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/kitti_twin.yaml",
                               {{"seed", std::to_string(seed)},
                                {"duration_s", "4"},
                                {"drive.speed_mps", "25"},
                                {"robot.realism", "typical"},
                                {"estimation.enabled", "false"},
                                {"outputs.mcap", "false"}});
    runner::RobotBuild robot = runner::BuildRunRobot(s);
    ASSERT_TRUE(robot.truth.stereo && robot.given.stereo);
    ASSERT_TRUE(
        robot.truth.stereo->left.Lens().is_zero() && robot.truth.stereo->right.Lens().is_zero() &&
        robot.given.stereo->left.Lens().is_zero() && robot.given.stereo->right.Lens().is_zero());
    const double true_offset_px = TrueDisparityOffsetPx(*robot.truth.stereo, *robot.given.stereo);
    const fs::path dir = fs::temp_directory_path() / "trackbed_kitti_twin_test";
    fs::remove_all(dir);
    runner::ClosedLoopOptions options;
    options.dir = dir;
    options.robot = std::move(robot);
    runner::ClosedLoop(s, std::move(options)).Run();
    const perception::KittiSequence sequence(dir / "images");
    ASSERT_EQ(sequence.size(), 41u);
    const VoScale measured = MeasureVoScale(sequence, false);
    const VoScale corrected = MeasureVoScale(sequence, true);
    std::printf(
        "seed %d: disparity offset true %+.3f px, estimated %+.3f px; per-frame median length "
        "ratio as measured %.4f, with the offset %.4f\n",
        seed, true_offset_px, corrected.offset_px, measured.length_ratio, corrected.length_ratio);
    EXPECT_NEAR(corrected.offset_px, true_offset_px, 0.4) << "seed " << seed;
    if (std::abs(true_offset_px) > 0.3) {
      const double m = std::abs(measured.length_ratio - 1.0);
      const double c = std::abs(corrected.length_ratio - 1.0);
      EXPECT_LT(c, m) << "seed " << seed;
      measured_bias += m;
      corrected_bias += c;
      ++with_offset;
    }
  }
  ASSERT_GE(with_offset, 3);
  EXPECT_GT(measured_bias / with_offset, 0.03);
  EXPECT_LT(corrected_bias, 0.5 * measured_bias);
}

}  // namespace
}  // namespace trackbed
