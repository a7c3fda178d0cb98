// Stereo visual odometry, the whole pipeline: on a synthetic rendered scene (accuracy,
// the motion bounds, a moving object, a rotation prior, a blank frame and recovery,
// determinism, bad input and options), and on the real KITTI 06 frames (end-point
// error, ATE, speed). Its motion-estimation unit has its own tests
// (stereo_motion_estimation_test.cpp).
#include "trackbed/estimation/stereo_visual_odometry.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "real_data.h"
#include "stereo_test_rig.h"
#include "trackbed/common/option_error.h"
#include "trackbed/estimation/absolute_orientation.h"
#include "trackbed/estimation/localization.h"
#include "trackbed/perception/kitti_sequence.h"

namespace trackbed::estimation {
namespace {

namespace fs = std::filesystem;
using stereo_test::kDegPerRad;
using stereo_test::Pose;
using stereo_test::RotationErrorDeg;
using stereo_test::TestCamera;
using stereo_test::TranslationError;

// ---------------------------------------------------------------------------------------
// The pipeline on a synthetic rendered scene: a textured floor and back wall seen by a
// moving rectified stereo pair (ray-cast per pixel, texture looked up bilinearly).

class SyntheticScene {
 public:
  SyntheticScene() {
    cv::Mat noise(kTexRows, kTexCols, CV_32F);
    cv::RNG rng(2024);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
    // Blobs of a few centimetres: larger than a pixel on the wall (1.4 cm at 7 m), so
    // the renderer's bilinear lookup does not alias.
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 3.0);
    // Contrast: standard deviation 60 gray levels around 128 (clipped when rendered).
    cv::Scalar mean, stddev;
    cv::meanStdDev(noise, mean, stddev);
    texture_ = (noise - mean[0]) * (60.0 / stddev[0]) + 128.0;
  }

  static geometry::StereoCamera Calibration() { return TestCamera(); }

  /// Left (right = false) or right image of the left camera at pose T_world_cam.
  cv::Mat Render(const Eigen::Isometry3d& T_world_cam, bool right) const {
    const geometry::StereoCamera c = TestCamera();
    Eigen::Isometry3d T = T_world_cam;
    if (right) T.translation() += T.linear() * Eigen::Vector3d(c.baseline_m, 0.0, 0.0);
    cv::Mat map_x(kHeight, kWidth, CV_32F), map_y(kHeight, kWidth, CV_32F);
    const Eigen::Vector3d o = T.translation();
    for (int v = 0; v < kHeight; ++v) {
      for (int u = 0; u < kWidth; ++u) {
        const Eigen::Vector3d ray = T.linear() * Eigen::Vector3d((u - c.left.cx) / c.left.fx,
                                                                 (v - c.left.cy) / c.left.fy, 1.0);
        // 1 cm texels. Wall z = kWallZ: column (x + 6)·100, row (y + 6)·100; floor
        // y = kFloorY (camera y is down): column (x + 6)·100, row 1200 + z·100.
        double t_wall = (kWallZ - o.z()) / ray.z();
        double t_floor = ray.y() > 1e-9 ? (kFloorY - o.y()) / ray.y() : 1e30;
        float tx, ty;
        if (t_floor < t_wall) {
          const Eigen::Vector3d p = o + t_floor * ray;
          tx = static_cast<float>((p.x() + 6.0) * 100.0);
          ty = static_cast<float>(1200.0 + p.z() * 100.0);
        } else {
          const Eigen::Vector3d p = o + t_wall * ray;
          tx = static_cast<float>((p.x() + 6.0) * 100.0);
          ty = static_cast<float>((p.y() + 6.0) * 100.0);
        }
        map_x.at<float>(v, u) = tx;
        map_y.at<float>(v, u) = ty;
      }
    }
    cv::Mat image_f, image;
    cv::remap(texture_, image_f, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
    image_f.convertTo(image, CV_8U);
    return image;
  }

  /// Camera pose of frame k: forward 8 cm per frame, drifting right, yawing 0.3°/frame,
  /// with a little pitch and roll.
  static Eigen::Isometry3d TruePose(int k) {
    return Pose(Eigen::Vector3d(0.001 * std::sin(0.5 * k), 0.3 * k / kDegPerRad, 0.0005 * k),
                Eigen::Vector3d(0.01 * k, 0.002 * std::sin(0.7 * k), 0.08 * k));
  }

  static constexpr int kWidth = 640, kHeight = 480;

 private:
  static constexpr int kTexCols = 1200, kTexRows = 2400;
  static constexpr double kWallZ = 7.0, kFloorY = 0.6;
  cv::Mat texture_;
};

TEST(StereoVisualOdometryTest, SyntheticSceneMotionIsRecovered) {
  const SyntheticScene scene;
  StereoVisualOdometry vo(SyntheticScene::Calibration());
  Eigen::Isometry3d T_world_cam0 = SyntheticScene::TruePose(0);
  double worst_deg = 0.0, worst_m = 0.0;
  int fewest_inliers = 1 << 30;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Isometry3d pose = SyntheticScene::TruePose(k);
    const VoFrameResult r =
        vo.Process(scene.Render(pose, false), scene.Render(pose, true), 0.1 * k);
    if (k == 0) {
      EXPECT_EQ(r.status, VoStatus::kFirstFrame);
      EXPECT_GT(r.features, 100);
      continue;
    }
    ASSERT_EQ(r.status, VoStatus::kOk) << "frame " << k << ": " << r.reason;
    const Eigen::Isometry3d truth = SyntheticScene::TruePose(k - 1).inverse() * pose;
    EXPECT_LT(RotationErrorDeg(r.T_prev_curr, truth), 0.05) << "frame " << k;
    EXPECT_LT(TranslationError(r.T_prev_curr, truth), 0.004) << "frame " << k;
    worst_deg = std::max(worst_deg, RotationErrorDeg(r.T_prev_curr, truth));
    worst_m = std::max(worst_m, TranslationError(r.T_prev_curr, truth));
    fewest_inliers = std::min(fewest_inliers, r.inliers);
    EXPECT_GT(r.inliers, 50);
    EXPECT_LE(r.inliers, r.matched);
    EXPECT_LE(r.matched, r.tracked);
    EXPECT_LT(r.reprojection_rms_px, 0.5);
    const Eigen::Isometry3d true_world = T_world_cam0.inverse() * pose;
    EXPECT_LT(TranslationError(r.T_world_cam, true_world), 0.004 * k) << "frame " << k;
  }
  std::printf("synthetic scene: worst frame-to-frame error %.4f deg, %.2f mm; fewest inliers %d\n",
              worst_deg, 1e3 * worst_m, fewest_inliers);
}

TEST(StereoVisualOdometryTest, MotionBeyondThePlatformsBoundsIsAFailureNotAMotion) {
  const SyntheticScene scene;
  StereoVisualOdometryOptions options;
  // Tighter than the synthetic scene's true per-frame motion.
  options.max_translation_per_frame_m = 1e-4;
  StereoVisualOdometry vo(SyntheticScene::Calibration(), options);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Isometry3d pose = SyntheticScene::TruePose(k);
    const VoFrameResult r =
        vo.Process(scene.Render(pose, false), scene.Render(pose, true), 0.1 * k);
    if (k == 0) continue;
    EXPECT_EQ(r.status, VoStatus::kImplausibleMotion) << r.reason;
    EXPECT_NE(r.reason.find("exceeds the per-frame bounds"), std::string::npos) << r.reason;
    EXPECT_EQ(r.inliers, 0);
    EXPECT_TRUE(r.T_prev_curr.isApprox(Eigen::Isometry3d::Identity()));
  }
  EXPECT_STREQ(ToString(VoStatus::kImplausibleMotion), "implausible_motion");
}

// Frame k of the synthetic scene in which, from frame `jump_frame` on, the part of the
// view between columns [x0, x1) is an object that has moved 0.06 m to the left at once
// (rendered from a camera 0.06 m to the right): features there move rigidly, but not
// with the camera. The whole view (x0 = 0, x1 = width) is the scene itself jumping.
std::pair<cv::Mat, cv::Mat> RenderWithJump(const SyntheticScene& scene, int k, int jump_frame,
                                           int x0, int x1) {
  const Eigen::Isometry3d pose = SyntheticScene::TruePose(k);
  std::pair<cv::Mat, cv::Mat> pair{scene.Render(pose, false), scene.Render(pose, true)};
  if (k < jump_frame) return pair;
  Eigen::Isometry3d moved = pose;
  moved.translation() += pose.linear() * Eigen::Vector3d(0.06, 0.0, 0.0);
  const cv::Rect region(x0, 0, x1 - x0, SyntheticScene::kHeight);
  scene.Render(moved, false)(region).copyTo(pair.first(region));
  scene.Render(moved, true)(region).copyTo(pair.second(region));
  return pair;
}

// The camera's true motion changes by under 2 mm per frame; 1 m/s² at 10 Hz allows 1 cm.
StereoVisualOdometryOptions TightDynamicsOptions() {
  StereoVisualOdometryOptions options;
  options.max_acceleration_mps2 = 1.0;
  options.max_angular_acceleration_dps2 = 100.0;
  return options;
}

TEST(StereoVisualOdometryTest, AConsensusOnAMovingObjectGivesWayToTheBackgroundsConsensus) {
  const SyntheticScene scene;
  // Three quarters of the view jump at frame 3: RANSAC's consensus is the object's.
  constexpr int kJump = 3, kX0 = 80, kX1 = 560;
  for (const bool check : {true, false}) {
    StereoVisualOdometryOptions options = TightDynamicsOptions();
    if (!check) options.max_acceleration_mps2 = options.max_angular_acceleration_dps2 = 1e6;
    StereoVisualOdometry vo(SyntheticScene::Calibration(), options);
    for (int k = 0; k <= kJump + 2; ++k) {
      const auto [left, right] = RenderWithJump(scene, k, kJump, kX0, kX1);
      const VoFrameResult r = vo.Process(left, right, 0.1 * k);
      if (k == 0) continue;
      ASSERT_EQ(r.status, VoStatus::kOk) << "frame " << k << ": " << r.reason;
      const Eigen::Isometry3d truth =
          SyntheticScene::TruePose(k - 1).inverse() * SyntheticScene::TruePose(k);
      const double error_m = TranslationError(r.T_prev_curr, truth);
      if (k != kJump) {
        EXPECT_FALSE(r.dynamics_constrained) << "frame " << k;
        continue;
      }
      if (check) {
        EXPECT_TRUE(r.dynamics_constrained);
        EXPECT_LT(error_m, 0.006);  // a quarter of the view's points: a little less accurate
        EXPECT_LT(RotationErrorDeg(r.T_prev_curr, truth), 0.05);
        EXPECT_LT(r.inliers, r.matched / 2);  // the background's quarter
        std::printf("moving object: the background's consensus %d of %d, error %.2f mm\n",
                    r.inliers, r.matched, 1e3 * error_m);
      } else {
        // Without the bounds the object's consensus is taken: the camera seems to move
        // with it.
        EXPECT_FALSE(r.dynamics_constrained);
        EXPECT_GT(error_m, 0.03);
        EXPECT_GT(r.inliers, r.matched / 2);
      }
    }
  }
}

TEST(StereoVisualOdometryTest, AJumpOfTheWholeViewIsAnInconsistentMotionAndTheNextFrameRecovers) {
  const SyntheticScene scene;
  constexpr int kJump = 3;
  StereoVisualOdometry vo(SyntheticScene::Calibration(), TightDynamicsOptions());
  Eigen::Isometry3d pose_before_jump = Eigen::Isometry3d::Identity();
  for (int k = 0; k <= kJump + 2; ++k) {
    const auto [left, right] = RenderWithJump(scene, k, kJump, 0, SyntheticScene::kWidth);
    const VoFrameResult r = vo.Process(left, right, 0.1 * k);
    if (k == kJump - 1) pose_before_jump = r.T_world_cam;
    if (k == kJump) {
      EXPECT_EQ(r.status, VoStatus::kInconsistentMotion) << r.reason;
      EXPECT_NE(r.reason.find("constant-velocity prediction"), std::string::npos) << r.reason;
      EXPECT_EQ(r.inliers, 0);
      EXPECT_TRUE(r.T_prev_curr.matrix().isIdentity());
      EXPECT_TRUE(r.T_world_cam.matrix() == pose_before_jump.matrix());
      std::printf("whole view jumps: %s\n", r.reason.c_str());
    } else if (k > kJump) {
      // No prediction after a failure: the next frame is taken as it comes, and the
      // scene is rigid again.
      ASSERT_EQ(r.status, VoStatus::kOk) << "frame " << k << ": " << r.reason;
      const Eigen::Isometry3d truth =
          SyntheticScene::TruePose(k - 1).inverse() * SyntheticScene::TruePose(k);
      EXPECT_LT(TranslationError(r.T_prev_curr, truth), 0.004) << "frame " << k;
    }
  }
  EXPECT_STREQ(ToString(VoStatus::kInconsistentMotion), "inconsistent_motion");
}

TEST(StereoVisualOdometryTest, ARotationPriorVetsEveryFramesConsensusEvenAfterAFailure) {
  const SyntheticScene scene;
  StereoVisualOdometry vo(SyntheticScene::Calibration());  // 2 deg from the prior
  const Eigen::Matrix3d off = Eigen::AngleAxisd(5.0 / kDegPerRad, Eigen::Vector3d::UnitY())
                                  .toRotationMatrix();  // a gyro 5 deg wrong
  for (int k = 0; k <= 4; ++k) {
    const Eigen::Isometry3d pose = SyntheticScene::TruePose(k);
    const Eigen::Isometry3d truth = SyntheticScene::TruePose(k - 1).inverse() * pose;
    const bool wrong_prior = k == 2 || k == 3;
    const Eigen::Matrix3d prior =
        wrong_prior ? Eigen::Matrix3d(truth.linear() * off) : Eigen::Matrix3d(truth.linear());
    const VoFrameResult r =
        vo.Process(scene.Render(pose, false), scene.Render(pose, true), 0.1 * k, &prior);
    if (k == 0) continue;
    if (wrong_prior) {
      // Frame 3 follows a failed frame: no constant-velocity prediction, but the prior.
      EXPECT_EQ(r.status, VoStatus::kInconsistentMotion) << "frame " << k;
      EXPECT_NE(r.reason.find("departs from the prior's by"), std::string::npos) << r.reason;
      EXPECT_TRUE(r.T_prev_curr.matrix().isIdentity());
    } else {
      ASSERT_EQ(r.status, VoStatus::kOk) << "frame " << k << ": " << r.reason;
      EXPECT_FALSE(r.dynamics_constrained);
      EXPECT_LT(TranslationError(r.T_prev_curr, truth), 0.004) << "frame " << k;
    }
  }
}

// The stack hands VO the gyro's rotation in the left camera's frame: a body turning
// about its z axis is a camera turning about its (pitched) y axis. Fed the true body
// rates, every frame keeps within the 2° bound and VO's pose is the body's; a stack
// that passed the body rotation on as the camera's would be 3°·√2 off and fail. Fed
// a gyro that turns about the body's x axis instead, the frames fail.
TEST(LocalizationStackTest, GyroRatesAreTurnedIntoTheCamerasFrameForVisualOdometry) {
  const SyntheticScene scene;
  const geometry::StereoCamera calibration = SyntheticScene::Calibration();
  // Body x forward, z up; the camera (OpenCV axes) looks along x, pitched 5° down.
  Eigen::Matrix3d R_body_cam;
  R_body_cam.col(0) = -Eigen::Vector3d::UnitY();  // right
  R_body_cam.col(1) = -Eigen::Vector3d::UnitZ();  // down
  R_body_cam.col(2) = Eigen::Vector3d::UnitX();   // forward
  R_body_cam = Eigen::AngleAxisd(5.0 / kDegPerRad, Eigen::Vector3d::UnitY()) * R_body_cam;
  Eigen::Isometry3d T_body_left = Eigen::Isometry3d::Identity();
  T_body_left.linear() = R_body_cam;
  T_body_left.translation() = Eigen::Vector3d(0.2, 0.06, 0.5);
  const double yaw_rate = 3.0 / kDegPerRad / 0.1;  // 3° per 0.1 s frame
  const auto body_pose = [&](int k) {              // turning left while driving 5 cm a frame
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_rate * 0.1 * k, Eigen::Vector3d::UnitZ()).matrix();
    T.translation() = Eigen::Vector3d(0.05 * k, 0.003 * k * k, 0.0);
    return T;
  };
  for (const bool right_axis : {true, false}) {
    LocalizationStack stack(LocalizationOptions{}, &calibration, T_body_left,
                            Eigen::Isometry3d::Identity());
    const Eigen::Vector3d rate =
        right_axis ? Eigen::Vector3d(0, 0, yaw_rate) : Eigen::Vector3d(yaw_rate, 0, 0);
    for (int k = 0; k <= 4; ++k) {
      if (k > 0) {
        for (int j = 1; j <= 20; ++j) stack.AddGyroSample(0.1 * (k - 1) + 0.005 * j, rate);
      } else {
        stack.AddGyroSample(0.0, rate);
      }
      // The scene's world is the first camera's frame.
      const Eigen::Isometry3d T_scene_cam = T_body_left.inverse() * body_pose(k) * T_body_left;
      const LocalizationFrameReport r = stack.AddStereoFrame(
          0.1 * k, scene.Render(T_scene_cam, false), scene.Render(T_scene_cam, true));
      if (k == 0) continue;
      if (right_axis) {
        ASSERT_EQ(r.vo.status, VoStatus::kOk) << "frame " << k << ": " << r.vo.reason;
        EXPECT_LT((stack.visual_odometry().translation() - body_pose(k).translation()).norm(), 0.01)
            << "frame " << k;
        EXPECT_LT(RotationErrorDeg(stack.visual_odometry(), body_pose(k)), 0.2) << "frame " << k;
      } else {
        EXPECT_EQ(r.vo.status, VoStatus::kInconsistentMotion) << "frame " << k;
      }
    }
  }
}

TEST(StereoVisualOdometryTest, BlankFrameFailsWithoutMotionAndTheNextFramesRecover) {
  const SyntheticScene scene;
  StereoVisualOdometry vo(SyntheticScene::Calibration());
  const cv::Mat blank(SyntheticScene::kHeight, SyntheticScene::kWidth, CV_8UC1, cv::Scalar(128));
  Eigen::Isometry3d pose_before_blank = Eigen::Isometry3d::Identity();
  for (int k = 0; k < 7; ++k) {
    const Eigen::Isometry3d pose = SyntheticScene::TruePose(k);
    const bool is_blank = k == 3;
    const VoFrameResult r =
        is_blank ? vo.Process(blank, blank, 0.1 * k)
                 : vo.Process(scene.Render(pose, false), scene.Render(pose, true), 0.1 * k);
    EXPECT_TRUE(r.T_world_cam.matrix().allFinite()) << "frame " << k;
    EXPECT_TRUE(r.T_prev_curr.matrix().allFinite()) << "frame " << k;
    if (k == 2) pose_before_blank = r.T_world_cam;
    if (is_blank) {
      EXPECT_TRUE(r.status == VoStatus::kTooFewFeatures || r.status == VoStatus::kTooFewInliers)
          << ToString(r.status);
      EXPECT_FALSE(r.reason.empty());
      EXPECT_EQ(r.inliers, 0);
      EXPECT_TRUE(r.T_prev_curr.matrix().isIdentity());
      EXPECT_TRUE(r.T_world_cam.matrix() == pose_before_blank.matrix());  // no motion
      std::printf("blank frame: %s (%s)\n", ToString(r.status), r.reason.c_str());
    } else if (k == 4) {
      // Nothing to track from the blank frame: still no motion, features re-detected.
      EXPECT_FALSE(r.ok());
      EXPECT_EQ(r.inliers, 0);
      EXPECT_TRUE(r.T_prev_curr.matrix().isIdentity());
      EXPECT_GT(r.features, 100);
    } else if (k > 4) {
      ASSERT_EQ(r.status, VoStatus::kOk) << "frame " << k << ": " << r.reason;
      const Eigen::Isometry3d truth = SyntheticScene::TruePose(k - 1).inverse() * pose;
      EXPECT_LT(RotationErrorDeg(r.T_prev_curr, truth), 0.05) << "frame " << k;
      EXPECT_LT(TranslationError(r.T_prev_curr, truth), 0.004) << "frame " << k;
    }
  }
}

TEST(StereoVisualOdometryTest, SameSeedSameImagesSameResult) {
  const SyntheticScene scene;
  std::vector<cv::Mat> left, right;
  for (int k = 0; k < 4; ++k) {
    left.push_back(scene.Render(SyntheticScene::TruePose(k), false));
    right.push_back(scene.Render(SyntheticScene::TruePose(k), true));
  }
  StereoVisualOdometry a(SyntheticScene::Calibration()), b(SyntheticScene::Calibration());
  for (int k = 0; k < 4; ++k) {
    const VoFrameResult ra =
        a.Process(left[static_cast<std::size_t>(k)], right[static_cast<std::size_t>(k)], 0.1 * k);
    const VoFrameResult rb =
        b.Process(left[static_cast<std::size_t>(k)], right[static_cast<std::size_t>(k)], 0.1 * k);
    EXPECT_EQ(ra.status, rb.status);
    EXPECT_EQ(ra.inliers, rb.inliers);
    EXPECT_TRUE(ra.T_world_cam.matrix() == rb.T_world_cam.matrix()) << "frame " << k;
  }
  // Reset starts over: the first frame again.
  a.Reset();
  EXPECT_EQ(a.Process(left[0], right[0], 0.0).status, VoStatus::kFirstFrame);
  EXPECT_TRUE(a.T_world_cam().matrix().isIdentity());
}

TEST(StereoVisualOdometryTest, BadInputThrows) {
  StereoVisualOdometry vo(SyntheticScene::Calibration());
  const cv::Mat a(48, 64, CV_8UC1, cv::Scalar(0)), b(48, 65, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(vo.Process(a, b, 0.0), std::invalid_argument);
  EXPECT_THROW(vo.Process(a, cv::Mat(48, 64, CV_8UC3), 0.0), std::invalid_argument);
  EXPECT_THROW(vo.Process(a, a, std::nan("")), std::invalid_argument);
  vo.Process(a, a, 1.0);
  EXPECT_THROW(vo.Process(a, a, 0.5), std::invalid_argument);  // time going backwards
  const cv::Mat big(96, 128, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(vo.Process(big, big, 2.0), std::invalid_argument);  // size changed
}

TEST(StereoVisualOdometryTest, InvalidOptionsNameTheDottedField) {
  const auto field_of = [](const StereoVisualOdometryOptions& o) {
    try {
      StereoVisualOdometry vo(SyntheticScene::Calibration(), o);
    } catch (const OptionError& e) {
      return e.field();
    }
    return std::string("(valid)");
  };
  StereoVisualOdometryOptions o;
  EXPECT_EQ(field_of(o), "(valid)");
  o.min_inliers = 2;
  EXPECT_EQ(field_of(o), "min_inliers");
  o = {};
  o.grid_cols = 0;
  EXPECT_EQ(field_of(o), "grid_cols");
  o = {};
  o.max_depth_m = 0.0;
  EXPECT_EQ(field_of(o), "max_depth_m");
  o = {};
  o.tracker.window_px = 4;
  EXPECT_EQ(field_of(o), "tracker.window_px");
  o = {};
  o.matcher.min_zncc = 2.0;
  EXPECT_EQ(field_of(o), "matcher.min_zncc");
  o = {};
  o.harris.k = 0.5;
  EXPECT_EQ(field_of(o), "harris.k");
  o = {};
  o.ransac.threshold_px = 0.0;
  EXPECT_EQ(field_of(o), "ransac.threshold_px");
  o = {};
  o.refinement.huber_px = -1.0;
  EXPECT_EQ(field_of(o), "refinement.huber_px");
  o = {};
  o.exhausted_cell_retry_frames = 0;
  EXPECT_EQ(field_of(o), "exhausted_cell_retry_frames");
}

// Corrupted streams: NaN stamps, stamps that go back or repeat, non-finite
// gyro or accelerometer readings and unusable images are set aside with their reason
// and counted; every estimate stays finite and ends exactly where the clean streams
// alone take it.
TEST(LocalizationStackTest, CorruptedInputsAreSetAsideAndChangeNoEstimate) {
  const SyntheticScene scene;
  const geometry::StereoCamera calibration = SyntheticScene::Calibration();
  Eigen::Isometry3d T_body_left = Eigen::Isometry3d::Identity();
  T_body_left.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // camera looking along body x
  LocalizationStack clean(LocalizationOptions{}, &calibration, T_body_left,
                          Eigen::Isometry3d::Identity());
  LocalizationStack dirty(LocalizationOptions{}, &calibration, T_body_left,
                          Eigen::Isometry3d::Identity());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const cv::Mat blank;
  for (int k = 0; k < 5; ++k) {
    for (int j = 1; j <= 10; ++j) {  // 10 encoder and IMU samples a frame
      const double t = 0.1 * k + 0.01 * j;
      const std::int64_t ticks = static_cast<std::int64_t>(400 * t);
      const Eigen::Vector3d gyro(0.0, 0.0, 0.05), accel(0.0, 0.0, 9.81);
      for (LocalizationStack* s : {&clean, &dirty}) {
        EXPECT_EQ(s->AddEncoderSample(t, ticks, ticks + j), InputStatus::kUsed);
        EXPECT_EQ(s->AddImuSample(t, gyro, accel), InputStatus::kUsed);
      }
      EXPECT_EQ(dirty.AddEncoderSample(nan, 1, 1), InputStatus::kTimeNotFinite);
      EXPECT_EQ(dirty.AddEncoderSample(t, 99999, 0), InputStatus::kTimeNotIncreasing);
      EXPECT_EQ(dirty.AddEncoderSample(t - 0.05, 0, 0), InputStatus::kTimeNotIncreasing);
      EXPECT_EQ(dirty.AddImuSample(inf, gyro, accel), InputStatus::kTimeNotFinite);
      EXPECT_EQ(dirty.AddImuSample(t, gyro, accel), InputStatus::kTimeNotIncreasing);
      EXPECT_EQ(dirty.AddImuSample(t + 0.001, Eigen::Vector3d(nan, 0, 0), accel),
                InputStatus::kValueNotFinite);
      EXPECT_EQ(dirty.AddGyroSample(t + 0.002, Eigen::Vector3d(0, inf, 0)),
                InputStatus::kValueNotFinite);
    }
    const Eigen::Isometry3d T_scene_cam = SyntheticScene::TruePose(k);
    const cv::Mat left = scene.Render(T_scene_cam, false), right = scene.Render(T_scene_cam, true);
    const double t = 0.1 * k + 0.1;
    EXPECT_EQ(clean.AddStereoFrame(t, left, right).input, InputStatus::kUsed);
    EXPECT_EQ(dirty.AddStereoFrame(t, left, right).input, InputStatus::kUsed);
    const LocalizationFrameReport again = dirty.AddStereoFrame(t, left, right);
    EXPECT_EQ(again.input, InputStatus::kTimeNotIncreasing);
    EXPECT_EQ(again.vo.status, VoStatus::kNotProcessed);
    EXPECT_EQ(again.vo.reason, "input set aside: time_not_increasing");
    EXPECT_EQ(dirty.AddStereoFrame(nan, left, right).input, InputStatus::kTimeNotFinite);
    EXPECT_EQ(dirty.AddStereoFrame(t + 0.05, blank, right).input, InputStatus::kImageInvalid);
    cv::Mat half;
    cv::resize(left, half, cv::Size(), 0.5, 0.5);
    EXPECT_EQ(dirty.AddStereoFrame(t + 0.05, half, half).input, InputStatus::kImageInvalid);
  }
  EXPECT_EQ(dirty.rejected().encoder, 150u);
  EXPECT_EQ(dirty.rejected().gyro, 200u);
  EXPECT_EQ(dirty.rejected().stereo, 20u);
  EXPECT_EQ(clean.rejected().encoder + clean.rejected().gyro + clean.rejected().stereo, 0u);
  for (const auto& [name, a, b] :
       {std::tuple{"wheel", clean.wheel_odometry(), dirty.wheel_odometry()},
        std::tuple{"no-slip", clean.wheel_odometry_noslip(), dirty.wheel_odometry_noslip()},
        std::tuple{"vo", clean.visual_odometry(), dirty.visual_odometry()},
        std::tuple{"fused", clean.fused(), dirty.fused()},
        std::tuple{"ekf", clean.ekf(), dirty.ekf()}}) {
    EXPECT_TRUE(b.matrix().allFinite()) << name;
    EXPECT_TRUE(a.matrix() == b.matrix()) << name;
  }
  EXPECT_GT(clean.wheel_odometry().translation().norm(), 0.0);
}

// ---------------------------------------------------------------------------------------
// Real data: KITTI odometry sequence 06, frames 0–50 (59.9 m, almost straight).

fs::path RealKittiDir() { return trackbed::testing_data::RealData("kitti06"); }

TEST(StereoVisualOdometryRealDataTest, Kitti06EndPointErrorWithinOneAndAHalfPercent) {
  TRACKBED_NEEDS_REAL_DATA(RealKittiDir());
  const perception::KittiSequence sequence(RealKittiDir());
  ASSERT_TRUE(sequence.has_poses());
  std::vector<cv::Mat> left, right;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    left.push_back(sequence.LoadLeft(k));
    right.push_back(sequence.LoadRight(k));
  }
  StereoVisualOdometry vo(sequence.calibration());
  std::vector<Eigen::Vector3d> p_est, p_gt;
  double process_s = 0.0;
  int min_inliers = 1 << 30;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    const VoFrameResult r = vo.Process(left[k], right[k], sequence.times_s()[k]);
    process_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (k > 0) {
      EXPECT_EQ(r.status, VoStatus::kOk) << "frame " << k << ": " << r.reason;
      min_inliers = std::min(min_inliers, r.inliers);
    }
    p_est.push_back(r.T_world_cam.translation());
    p_gt.push_back(sequence.poses()[k].translation());
  }
  double length = 0.0;
  for (std::size_t k = 1; k < p_gt.size(); ++k) length += (p_gt[k] - p_gt[k - 1]).norm();
  const double end_error = (p_est.back() - p_gt.back()).norm();
  const SimilarityTransform S = HornAbsoluteOrientationAnyMinimizer(p_est, p_gt);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < p_est.size(); ++k)
    sum_sq += (p_gt[k] - S.Apply(p_est[k])).squaredNorm();
  const double ate = std::sqrt(sum_sq / static_cast<double>(p_est.size()));
  const double n = static_cast<double>(sequence.size());
  std::printf(
      "kitti06: %zu frames, %.1f m; end-point error %.3f m (%.2f %%), ATE (SE(3)) %.3f m; "
      "fewest inliers %d; %.1f frames/s (%.2f ms per frame)\n",
      sequence.size(), length, end_error, 100.0 * end_error / length, ate, min_inliers,
      n / process_s, 1e3 * process_s / n);
  EXPECT_LE(end_error, 0.015 * length);
  EXPECT_LT(ate, 0.3);
  EXPECT_GE(min_inliers, 50);
}

}  // namespace
}  // namespace trackbed::estimation
