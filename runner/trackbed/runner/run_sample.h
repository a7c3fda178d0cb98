// What a closed-loop run produces at each of its rates, as records: the encoder-rate
// sample of ground truth with the estimates beside it, a stereo pair, and the
// localization stack's work on a pair.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "trackbed/estimation/localization.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/robot/tracked_vehicle.h"

namespace trackbed::runner {

/// The localization stack's estimates at one encoder sample (all T_world_body).
struct EstimateSample {
  double t_s = 0.0;
  Eigen::Isometry3d wheel_odometry, wheel_odometry_noslip, fused, ekf;
  bool has_camera = false;  ///< fused (and visual odometry) exist
  /// Ham et al.'s fusion beside a `fused` of another method
  /// (estimation.fusion.method: covariance); none otherwise.
  std::optional<Eigen::Isometry3d> fused_ham2012;
  estimation::TrackSlip slip;
  /// Each estimator's pose covariance, where it has one (estimation::PoseCovariances).
  estimation::PoseCovariances covariances;
};

/// What the runner records at the encoder rate.
struct RunSample {
  double t_s = 0.0;
  robot::ChassisState chassis;            ///< Ground truth.
  robot::TrackState tracks[2];            ///< Ground truth per track (left, right).
  long long ticks[2] = {0, 0};            ///< Encoder counts (left, right).
  const std::string* material = nullptr;  ///< Material under the centre of mass.
  /// The localization stack's estimates at this sample (null when estimation is off).
  const EstimateSample* estimate = nullptr;
};

/// One stereo pair as the robot's cameras saw it.
struct StereoFrame {
  std::int64_t index = 0;  ///< 0, 1, 2, … at the camera rate.
  double t_s = 0.0;
  const GrayImage* left = nullptr;
  const GrayImage* right = nullptr;
  Eigen::Isometry3d T_world_left;  ///< Ground truth of the left camera (OpenCV axes).
  Eigen::Isometry3d T_world_right;
  const robot::StereoRig* rig = nullptr;
  bool blackout = false;         ///< A camera fault blanked this pair (robot.stereo.blackouts_s).
  double exposure_time_s = 0.0;  ///< how long each row's shutter was open [s]
  double gain = 1.0;             ///< the analog gain the auto-exposure set (1 without it)
  /// The encoders' last reading (counts since start), taken with this pair.
  std::int64_t ticks[2] = {0, 0};
};

/// An estimate of the body's pose handed to the loop from outside it (a user's own
/// estimator, ClosedLoop::ReportEstimate), with ground truth at the same time.
struct ExternalEstimate {
  const std::string* name = nullptr;  ///< the estimator's name (metrics.json `estimators`)
  double t_s = 0.0;
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();       ///< the estimate
  Eigen::Isometry3d T_world_body_true = Eigen::Isometry3d::Identity();  ///< ground truth
};

/// The stack's work on one stereo frame.
struct LocalizationFrame {
  double t_s = 0.0;
  bool camera_blackout = false;
  estimation::LocalizationFrameReport report;
  Eigen::Isometry3d visual_odometry;  ///< T_world_body after this frame
};

}  // namespace trackbed::runner
