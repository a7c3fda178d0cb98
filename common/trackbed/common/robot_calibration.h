// What the robot's software is told about the robot it runs on: its stereo camera's,
// IMU's and vehicle's calibration, as a run folder's stereo_calibration.json,
// imu_calibration.json and vehicle_calibration.json hold them, and as a user's own
// calibration folder (`robot.calibration_dir`) gives them. The same structs hold the
// robot as built in ground_truth_calibration.json, so that the given and the true
// values have the same field names (docs/calibration.md). Read and written by the
// config archive (archive.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "trackbed/common/archive.h"
#include "trackbed/common/archive_eigen.h"
#include "trackbed/common/pinhole_camera.h"
#include "trackbed/common/stereo_camera.h"

namespace trackbed::calibration {

/// One camera's intrinsics as a calibration file lists them (no image size: the pair
/// shares it).
struct CameraIntrinsics {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;  ///< [px]
  /// The lens (absent: an ideal pinhole, and the file has no `distortion`).
  std::optional<geometry::LensDistortion> distortion;

  /// The lens, an ideal pinhole when none is given.
  geometry::LensDistortion Lens() const { return distortion.value_or(geometry::LensDistortion{}); }
  bool operator==(const CameraIntrinsics& o) const {
    return fx == o.fx && fy == o.fy && cx == o.cx && cy == o.cy && Lens() == o.Lens();
  }
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("fx", &fx, archive::kRequired);
    a->Visit("fy", &fy, archive::kRequired);
    a->Visit("cx", &cx, archive::kRequired);
    a->Visit("cy", &cy, archive::kRequired);
    a->Visit("distortion", &distortion, archive::kOmitEmpty);
  }
};

/// stereo_calibration.json: the two cameras as calibrated, not necessarily a rectified
/// pair, and where they sit on the body. The left camera's intrinsics are the file's
/// top-level fx, fy, cx, cy (the form of a rectified pair, which has one camera); the
/// right camera's are `right`.
struct StereoCalibration {
  int width_px = 0, height_px = 0;
  CameraIntrinsics left, right;
  /// Distance between the optical centres [m] (> 0; for a rectified pair, the offset
  /// of the right camera along the left camera's x axis).
  double baseline_m = 0.0;
  /// The cameras (OpenCV axes: x right, y down, z forward) in the body frame.
  Eigen::Isometry3d T_body_left = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_body_right = Eigen::Isometry3d::Identity();

  /// The left or right camera, with its lens.
  geometry::PinholeCamera LeftCamera() const { return Camera(left); }
  geometry::PinholeCamera RightCamera() const { return Camera(right); }
  /// A camera of this pair's image size with intrinsics `k`.
  geometry::PinholeCamera Camera(const CameraIntrinsics& k) const;
  /// The right camera in the left camera's frame.
  Eigen::Isometry3d T_left_right() const { return T_body_left.inverse() * T_body_right; }
  /// Whether the pair is rectified as given: the same intrinsics and orientation, and
  /// the right camera `baseline_m` along the left camera's x axis (to 1e-9 m), and ideal
  /// pinhole lenses. Then
  /// `RectifiedPair()` is the pair, exactly.
  bool IsRectified() const;
  geometry::StereoCamera RectifiedPair() const { return {LeftCamera(), baseline_m}; }

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  bool operator==(const StereoCalibration& o) const {
    return width_px == o.width_px && height_px == o.height_px && left == o.left &&
           right == o.right && baseline_m == o.baseline_m &&
           T_body_left.matrix() == o.T_body_left.matrix() &&
           T_body_right.matrix() == o.T_body_right.matrix();
  }

  /// The file's keys but `convention` and `source` (the file form adds them), in the
  /// order the file lists them.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("width_px", &width_px, archive::kRequired);
    a->Visit("height_px", &height_px, archive::kRequired);
    a->Visit("fx", &left.fx, archive::kRequired);
    a->Visit("fy", &left.fy, archive::kRequired);
    a->Visit("cx", &left.cx, archive::kRequired);
    a->Visit("cy", &left.cy, archive::kRequired);
    a->Visit("distortion", &left.distortion, archive::kOmitEmpty);
    a->Visit("baseline_m", &baseline_m, archive::kRequired);
    a->Visit("T_body_left", &T_body_left, archive::kRequired);
    a->Visit("T_body_right", &T_body_right, archive::kRequired);
    a->Visit("right", &right, archive::kRequired);
  }
};

/// imu_calibration.json: how the IMU's readings relate to the body's motion.
///   gyro  = gyro_axes · R_imu_body · ω_body + gyro_g_sensitivity · f_imu + bias + noise
///   accel = accel_axes · f_imu + bias + noise,   f_imu = R_imu_body · f_body
/// with R_imu_body = R_body_imuᵀ and f the specific force. The axes matrices hold the
/// scale factors on the diagonal and the cross-axis sensitivities (axis misalignment)
/// off it; identity is a perfect sensor.
struct ImuCalibration {
  Eigen::Matrix3d gyro_axes = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d accel_axes = Eigen::Matrix3d::Identity();
  /// Gyro rate per unit specific force [rad/s per m/s²].
  Eigen::Matrix3d gyro_g_sensitivity = Eigen::Matrix3d::Zero();
  /// The IMU's axes in the body frame (a rotation).
  Eigen::Matrix3d R_body_imu = Eigen::Matrix3d::Identity();
  /// Camera–IMU time offset [s]: a frame stamped t_cam was exposed at IMU time
  /// t_cam + camera_time_offset_s (Kalibr's timeshift_cam_imu).
  double camera_time_offset_s = 0.0;

  /// Whether the gyro's readings need no correction (identity gyro axes, no
  /// g-sensitivity, the IMU aligned with the body); the accelerometer's axes do not
  /// enter the body rate then.
  bool IsIdentity() const;

  void Validate() const;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("gyro_axes", &gyro_axes, archive::kRequired);
    a->Visit("accel_axes", &accel_axes, archive::kRequired);
    a->Visit("gyro_g_sensitivity", &gyro_g_sensitivity, archive::kRequired);
    a->Visit("R_body_imu", &R_body_imu, archive::kRequired);
    a->Visit("camera_time_offset_s", &camera_time_offset_s, archive::kRequired);
  }
};

/// vehicle_calibration.json: the drive train as the wheel odometry models it.
struct VehicleCalibration {
  /// Effective sprocket radius of each track [m], > 0: track speed over sprocket rate.
  double sprocket_radius_left_m = 0.0;
  double sprocket_radius_right_m = 0.0;
  /// Distance between the track centrelines [m], > 0.
  double track_gauge_m = 0.0;
  /// ICR expansion factor χ (B_eff = χ·B), from the ICR calibration run
  /// (scenes/calibration/icr_turns.yaml); absent from the truth, which has no χ.
  std::optional<double> icr_expansion;

  void Validate() const;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("sprocket_radius_left_m", &sprocket_radius_left_m, archive::kRequired);
    a->Visit("sprocket_radius_right_m", &sprocket_radius_right_m, archive::kRequired);
    a->Visit("track_gauge_m", &track_gauge_m, archive::kRequired);
    a->Visit("icr_expansion", &icr_expansion, archive::kOmitEmpty);
  }
};

/// Where each given file came from (a run folder's calibration files say it in their
/// `source` key): the truth, a drawn calibration error, a calibration run, a folder.
struct RobotCalibration {
  std::optional<StereoCalibration> stereo;  ///< none: the robot has no stereo camera
  ImuCalibration imu;
  VehicleCalibration vehicle;
  /// Per file: how the values were obtained (written as each file's `source`).
  std::string stereo_source, imu_source, vehicle_source;
};

/// The files of a calibration folder.
inline constexpr const char* kStereoFile = "stereo_calibration.json";
inline constexpr const char* kImuFile = "imu_calibration.json";
inline constexpr const char* kVehicleFile = "vehicle_calibration.json";
inline constexpr const char* kGroundTruthFile = "ground_truth_calibration.json";

/// Each file's JSON text (with its `source`), as a run folder holds it.
std::string StereoCalibrationJson(const StereoCalibration& c, const std::string& source);
std::string ImuCalibrationJson(const ImuCalibration& c, const std::string& source);
std::string VehicleCalibrationJson(const VehicleCalibration& c, const std::string& source);
/// ground_truth_calibration.json: one object per given file, same field names.
std::string GroundTruthCalibrationJson(const RobotCalibration& truth);

/// Reads a calibration folder: its imu_calibration.json and vehicle_calibration.json,
/// and its stereo_calibration.json when `with_stereo`. Throws archive::Error whose
/// message names the file and the key, for a missing file or a malformed one.
RobotCalibration ReadCalibrationFolder(const std::filesystem::path& dir, bool with_stereo);

}  // namespace trackbed::calibration
