// The localization stack of Ham et al. 2012 on one robot's sensor streams:
// slip-aware wheel odometry, the no-slip baseline, stereo visual odometry and
// their fuzzy fusion. It sees encoder counts, stereo images and the camera's
// calibration and mounting — never the simulator — so it runs unchanged on
// logged real data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/common/pose2.h"
#include "trackbed/common/robot_calibration.h"
#include "trackbed/common/stereo_camera.h"
#include "trackbed/estimation/covariance_fusion.h"
#include "trackbed/estimation/ekf_odometry.h"
#include "trackbed/estimation/fusion_weight_rise.h"
#include "trackbed/estimation/fuzzy_fusion.h"
#include "trackbed/estimation/gyro_bias.h"
#include "trackbed/estimation/gyro_rotation.h"
#include "trackbed/estimation/imu_correction.h"
#include "trackbed/estimation/pose_uncertainty.h"
#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/estimation/wheel_odometry.h"
#include "trackbed/perception/stereo_rectifier.h"

namespace trackbed::estimation {

struct LocalizationOptions {
  /// Wheel odometry (its `estimate_slip` is set per estimator; its geometry comes from
  /// the robot: WheelOdometryOptions).
  WheelOdometryOptions wheel;
  /// Stereo visual odometry (StereoVisualOdometryOptions::TrackedRobot() for the tracked
  /// robot, KittiCar() for KITTI's car).
  StereoVisualOdometryOptions vo;
  /// The fusion's rule base and weight dynamics.
  FusionOptions fusion;
  /// Inliers a VO frame needs before its velocity updates the slip estimate (slip is
  /// measured against VO whenever VO is valid, with enough inliers: docs/localization.md,
  /// our reading of Ham et al. 2012 eqs. 1–5), >= 0; below the VO's own minimum it is
  /// that minimum.
  int min_inliers_for_slip = 30;
  /// On a failed VO frame, visual odometry's own pose goes on with the last valid
  /// frame's velocity (a constant-velocity motion model, as VO pipelines bridge a lost
  /// frame) for up to this long after that frame [s], >= 0; beyond it, it holds. 0:
  /// it holds at once. The fusion takes a failed frame's increment from the wheels
  /// whatever this is, and the slip estimate never sees a coasted motion.
  double vo_coast_time_s = 1.0;
  /// Pair each stereo frame with the gyro at the instant it was exposed on the IMU's
  /// clock, its stamp plus the given calibration's camera–IMU time offset
  /// (imu.camera_time_offset_s, Kalibr's timeshift_cam_imu): VO's rotation prior is the
  /// gyro's rotation between two frames' exposures (IntegrateGyro, gyro_rotation.h;
  /// past the newest sample its rate is held). Off: the samples up to the frame's
  /// stamp, as if the offset were 0.
  bool apply_camera_time_offset = false;
  /// The EKF baseline (wheel odometry + gyro + visual odometry).
  EkfOdometryOptions ekf;
  /// The gyro as a rotation source: its bias from standstills, the gyro-led wheel
  /// odometry and fusion (gyro_bias.h).
  GyroHeadingOptions gyro;
  /// The bound beyond which an estimate's own covariance says it is lost
  /// (pose_uncertainty.h); the stack reports, the run scores it.
  LocalizationLostOptions localization_lost;
  /// The IMU's given calibration (imu_calibration.json): AddImuSample turns its
  /// readings into body rates with it. Known at run time, no key (see Serialize).
  calibration::ImuCalibration imu;
  /// The gyro's data-sheet noise (the IMU part's). Known at run time, no key.
  GyroModel gyro_model;

  void Validate() const;

  /// The tracked robot's stack: the defaults with StereoVisualOdometryOptions::
  /// TrackedRobot().
  static LocalizationOptions TrackedRobot() {
    LocalizationOptions o;
    o.vo = StereoVisualOdometryOptions::TrackedRobot();
    return o;
  }

  /// The keys of the fields that are knobs (e.g. the scenario's `estimation.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h). Not visited: `imu`, the given calibration,
  /// `gyro_model`, the IMU's data sheet, and the wheels' geometry
  /// (WheelOdometryOptions::Serialize).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("wheel", &wheel);
    a->Visit("vo", &vo);
    a->Visit("fusion", &fusion);
    a->Visit("min_inliers_for_slip", &min_inliers_for_slip);
    a->Visit("vo_coast_time_s", &vo_coast_time_s);
    a->Visit("apply_camera_time_offset", &apply_camera_time_offset);
    a->Visit("ekf", &ekf);
    a->Visit("gyro", &gyro);
    a->Visit("localization_lost", &localization_lost);
  }
};

/// Whether the stack used a sensor input, or why it set it aside. Streams from real
/// hardware and logs carry NaN stamps, stamps that go back (a driver's clock jump, a
/// message reordered in transport) and non-finite readings: each such input is dropped
/// and counted, so that no estimate takes a NaN or integrates over a negative interval
/// from it, and the caller hears why.
enum class InputStatus : std::uint8_t {
  kUsed,
  kTimeNotFinite,      ///< the stamp is NaN or infinite
  kTimeNotIncreasing,  ///< the stamp is not after the stream's last used one
  kValueNotFinite,     ///< a reading is NaN or infinite
  kImageInvalid,       ///< an image is empty, not 8-bit grey or not the calibration's size
};

/// Short lower-case name ("used", "time_not_finite", "time_not_increasing",
/// "value_not_finite", "image_invalid").
const char* ToString(InputStatus status);

/// Inputs set aside so far, per stream.
struct RejectedInputs {
  std::size_t encoder = 0, gyro = 0, stereo = 0;
};

/// What one stereo frame did to the estimates.
struct LocalizationFrameReport {
  /// Whether the frame was used; a frame set aside changes no estimate.
  InputStatus input = InputStatus::kUsed;
  VoFrameResult vo;
  bool vo_valid = false;           ///< VO produced a motion (enough inliers).
  bool vo_coasted = false;         ///< VO failed; its pose went on at the last velocity.
  double slip_velocity_mps = 0.0;  ///< Fusion input: larger track |slip| estimate.
  double features = 0.0;           ///< Fusion input: VO inliers.
  double w = 1.0;                  ///< Weight of wheel odometry applied in this step.
  double w_rule = 1.0;             ///< The rule base's weight for this frame alone.
  TrackSlip slip;                  ///< Estimated slip of both tracks.
  /// VO's motion as the body's: T_prev_curr of the body (p_prev = T · p_curr), and the
  /// covariance of the left increment of its inverse (curr from prev) in the current
  /// body's axes [m², m·rad, rad²] (VoFrameResult::covariance carried by the camera's
  /// mounting, TransformMotionCovariance). Identity and zero unless vo_valid;
  /// the covariance is zero also where VO's is not valid.
  Eigen::Isometry3d vo_body_motion = Eigen::Isometry3d::Identity();
  MotionCovarianceMatrix vo_body_covariance = MotionCovarianceMatrix::Zero();
};

/// Runs the estimators side by side. Every estimator starts at the robot's
/// true initial pose (docs/run_folder.md), planar ones at its height. Not copyable.
class LocalizationStack {
 public:
  /// `T_body_left`: the left camera (OpenCV axes) in the body frame.
  /// `camera` (the calibrated rectified pair) null: no camera, wheel odometry only.
  LocalizationStack(const LocalizationOptions& options, const geometry::StereoCamera* camera,
                    const Eigen::Isometry3d& T_body_left, const Eigen::Isometry3d& T_world_body0);
  /// From the stereo camera's given calibration (stereo_calibration.json; null: no
  /// camera): a pair that is not rectified as given is rectified from it
  /// (perception::StereoRectifier) before visual odometry sees it.
  LocalizationStack(const LocalizationOptions& options,
                    const calibration::StereoCalibration* stereo,
                    const Eigen::Isometry3d& T_world_body0);
  ~LocalizationStack();
  LocalizationStack(const LocalizationStack&) = delete;
  LocalizationStack& operator=(const LocalizationStack&) = delete;

  /// Each Add* uses its input or sets it aside (InputStatus): stamps must be finite and
  /// increase within each stream, readings finite, images 8-bit grey of the calibration's
  /// size.
  InputStatus AddEncoderSample(double t_s, std::int64_t left_ticks, std::int64_t right_ticks);
  /// The IMU gyro's rates about the body axes [rad/s]: z for the EKF baseline; all
  /// three, integrated from one stereo frame to the next, are the rotation prior that
  /// vets visual odometry's consensus (StereoVisualOdometryOptions::
  /// max_rotation_prior_error_deg). Only VO frames with gyro samples since the last
  /// frame get a prior.
  InputStatus AddGyroSample(double t_s, const Eigen::Vector3d& rate_radps);
  /// An IMU reading in the IMU's own axes: turned into the body's rate with the given
  /// calibration (LocalizationOptions::imu), then as AddGyroSample.
  InputStatus AddImuSample(double t_s, const Eigen::Vector3d& gyro_radps,
                           const Eigen::Vector3d& accel_mps2);
  LocalizationFrameReport AddStereoFrame(double t_s, const cv::Mat& left, const cv::Mat& right);

  /// Current estimates of T_world_body.
  Eigen::Isometry3d wheel_odometry() const;
  Eigen::Isometry3d wheel_odometry_noslip() const;
  Eigen::Isometry3d visual_odometry() const;
  Eigen::Isometry3d fused() const;
  /// Ham et al.'s fusion when `fused` is another method (FusionOptions::method); none
  /// otherwise.
  std::optional<Eigen::Isometry3d> fused_ham2012() const;
  Eigen::Isometry3d ekf() const;
  /// Each estimator's pose covariance now, where it has one (PoseCovariances).
  PoseCovariances pose_covariances() const;
  /// The zero-velocity estimate of the gyro's bias.
  const ZeroVelocityGyroBias& gyro_bias() const { return zupt_; }
  /// The slip estimate of the `wheel_odometry` estimator.
  const TrackSlip& slip() const { return wheel_led().slip(); }
  /// Inputs set aside so far.
  const RejectedInputs& rejected() const { return rejected_; }

 private:
  LocalizationStack(const LocalizationOptions& options,
                    std::shared_ptr<const perception::StereoRectifier> rectifier,
                    const Eigen::Isometry3d& T_world_body0);
  // A rectified pair's frame.
  LocalizationFrameReport ProcessStereoFrame(double t_s, const cv::Mat& left, const cv::Mat& right);
  // The gyro's rotation over the last frame interval in the left camera's frame, or
  // null where there is none (into *R).
  const Eigen::Matrix3d* RotationPrior(double t_s, Eigen::Matrix3d* R);
  // The gyro-led wheel odometry's step at a frame: VO's rotation weighed against the
  // gyro's, the slip estimate, the covariance fusion.
  void GyroLedFrame(double t_s, const LocalizationFrameReport& report,
                    const std::optional<geometry::Pose2>& vo_increment,
                    const std::optional<Eigen::Matrix3d>& vo_covariance);
  // The wheel odometry reported as `wheel_odometry`, and the one Ham's fusion takes.
  const WheelOdometry& wheel_led() const;
  const WheelOdometry& wheel_for_fusion() const;
  // The gyro's bias variance about z now.
  double GyroBiasVarianceZ() const;
  // Why a frame at t_s with these images is set aside, or kUsed.
  InputStatus CheckStereoFrame(double t_s, const cv::Mat& left, const cv::Mat& right) const;

  LocalizationOptions options_;
  // Rectifies each pair when the given one is not rectified; null otherwise.
  std::shared_ptr<const perception::StereoRectifier> rectifier_;
  cv::Mat rectified_left_, rectified_right_;
  Eigen::Isometry3d T_body_left_;
  double z0_;
  WheelOdometry wheel_, wheel_noslip_;
  std::unique_ptr<StereoVisualOdometry> vo_;
  FuzzyFusionWeight fuzzy_;
  FusedOdometry fused_;
  EkfOdometry ekf_;
  FusionWeightRise weight_;  // the applied wheel weight
  ImuCorrection imu_;        // readings to body rates (LocalizationOptions::imu)
  Eigen::Isometry3d T_world_body_vo_;
  // The covariance of visual odometry's planar pose (+∞ once a frame had no motion).
  Eigen::Matrix3d vo_pose_covariance_ = Eigen::Matrix3d::Zero();
  // The body's motion over the last valid VO frame, its interval and its time (coasting).
  Eigen::Isometry3d vo_last_motion_ = Eigen::Isometry3d::Identity();
  double vo_last_dt_ = 0.0, t_vo_valid_ = 0.0;
  bool has_vo_motion_ = false;
  // Wheel pose and time at the last stereo frame: the fusion step's interval.
  // (Declared after the estimators: initialised from the initial pose.)
  geometry::Pose2 wheel_at_frame_;
  double t_frame_ = 0.0;
  bool has_frame_ = false;
  // The body's rotation since the last stereo frame, integrated from the gyro.
  Eigen::Matrix3d R_gyro_since_frame_ = Eigen::Matrix3d::Identity();
  double t_gyro_ = 0.0;
  bool has_gyro_ = false, gyro_since_frame_ = false;
  // With apply_camera_time_offset: the gyro's samples not yet wholly before the last
  // frame's exposure, and that exposure's time on the IMU's clock.
  std::deque<GyroInterval> gyro_intervals_;
  double t_exposure_ = 0.0;
  bool has_exposure_ = false;
  // The last used encoder stamp; inputs set aside.
  double t_encoder_ = 0.0;
  bool has_encoder_ = false;
  RejectedInputs rejected_;
  // The gyro as a rotation source (GyroHeadingOptions): the bias from standstills; the
  // gyro-led wheel odometry (null unless a key needs it), the heading the gyro turned
  // since its last encoder sample, the vertical in the body's axes (low-passed specific
  // force); the covariance fusion (null unless it is the method) and the gyro-led
  // wheels' pose at the last frame.
  ZeroVelocityGyroBias zupt_;
  std::unique_ptr<WheelOdometry> wheel_gyro_;
  double gyro_yaw_since_encoder_ = 0.0;
  bool gyro_yaw_pending_ = false;
  Eigen::Vector3d up_body_ = Eigen::Vector3d::UnitZ();
  double t_accel_ = 0.0;
  bool has_accel_ = false;
  std::unique_ptr<CovarianceFusion> covariance_fused_;
  geometry::Pose2 wheel_gyro_at_frame_;
  double gate_1dof_ = 0.0;
};

}  // namespace trackbed::estimation
