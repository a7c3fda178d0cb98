// The robot as built and the calibration its software is given. A real robot is not
// its drawing: its tracks' effective radii, its IMU's scale factors and axes, its
// cameras' lenses and mounting differ from the design, and its software knows them
// only as well as they were calibrated. Each run draws the robot as built around the
// design, seeded (`robot.as_built_seed`); the plant (physics, renderer, sensors) uses
// it, and the robot software gets the calibration files (docs/calibration.md).
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "trackbed/common/archive.h"
#include "trackbed/common/archive_eigen.h"
#include "trackbed/common/robot_calibration.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/robot/tracked_vehicle.h"

namespace trackbed::robot {

/// `robot.realism`: a documented set of imperfections (docs/calibration.md gives each
/// value's source). kIdeal: the robot is its design and the software is given the truth.
enum class Realism { kIdeal, kTypical, kHarsh };

/// How the wheel odometry's sprocket radii are obtained.
enum class WheelCalibration {
  kTruth,        ///< the robot as built (ideal)
  kStraightRun,  ///< the straight calibration run (scenes/calibration/straight_line.yaml)
};

}  // namespace trackbed::robot

namespace trackbed::archive {

template <>
struct Codec<robot::WheelCalibration> {
  static void Read(const Node& node, const std::string& path, Wording wording,
                   robot::WheelCalibration* value);
  static Node Write(robot::WheelCalibration value);
};

}  // namespace trackbed::archive

namespace trackbed::robot {

/// The robot's imperfections (`robot.imperfections.*`), each a 1σ spread of a
/// zero-mean Gaussian per track, axis, term or camera unless it says otherwise. A key
/// left out takes the realism profile's value (Resolve); a run folder's scenario.yaml
/// lists them all.
struct Imperfections {
  // The vehicle as built (relative spreads).
  std::optional<double> sprocket_radius_rel_std;
  std::optional<double> track_gauge_rel_std;
  /// What the wheel odometry's radii come from.
  std::optional<WheelCalibration> wheel_calibration;
  // The IMU as built. The software assumes the datasheet's ideal part aligned with the
  // body (no user calibration), so these are also its errors.
  std::optional<double> gyro_scale_std;                    ///< [-], per axis
  std::optional<double> gyro_misalignment_std_deg;         ///< cross-axis term, each of 6
  std::optional<double> gyro_g_sensitivity_std_dps_per_g;  ///< [°/s/g], each of 9 terms
  std::optional<double> accel_scale_std;                   ///< [-], per axis
  std::optional<double> accel_misalignment_std_deg;        ///< cross-axis term, each of 6
  std::optional<double> imu_mount_std_deg;                 ///< IMU axes to body, per axis
  // The cameras as built, about the design.
  std::optional<double> focal_length_rel_std;  ///< fx, fy of each camera
  std::optional<double> principal_point_std_px;
  std::optional<Eigen::Vector3d> stereo_translation_std_mm;  ///< right camera, left axes
  std::optional<Eigen::Vector3d> stereo_rotation_std_mrad;   ///< about the left axes
  std::optional<double> camera_mount_std_deg;                ///< the pair on the body
  // The camera calibration's error: the given values about the cameras as built.
  std::optional<double> focal_length_calibration_rel_std;
  std::optional<double> principal_point_calibration_std_px;
  std::optional<Eigen::Vector3d> stereo_translation_calibration_std_mm;
  std::optional<Eigen::Vector3d> stereo_rotation_calibration_std_mrad;
  std::optional<double> camera_mount_calibration_std_deg;
  /// Each camera's lens coefficients as calibrated about the lens as built: the
  /// spreads of k1, k2, p1, p2 (k3 and k4 are given as built), drawn independently.
  std::optional<Eigen::Vector4d> distortion_calibration_std;
  /// Each camera's lens as calibrated, stated as the RMS over the image of the error in
  /// where the calibrated lens puts a point [px] (not a spread per coefficient): the
  /// coefficients' error is drawn correlated, as a fit over the image leaves them
  /// (lens_calibration_error.h). Adds to `distortion_calibration_std`'s draw.
  std::optional<double> distortion_calibration_rms_px;
  /// The camera's time offset as built [s] (a constant, not a spread): a frame stamped
  /// t was exposed at t + offset (ImuCalibration::camera_time_offset_s).
  std::optional<double> camera_time_offset_s;

  /// Every key set: a key given here, else the profile's.
  Imperfections Resolve(Realism profile) const;
  /// Throws OptionError naming the first negative spread or value out of range.
  void Validate() const;

  template <class Archive>
  void Serialize(Archive* a) {
    constexpr archive::Field kOpt = archive::kOmitEmpty;
    a->Visit("sprocket_radius_rel_std", &sprocket_radius_rel_std, kOpt);
    a->Visit("track_gauge_rel_std", &track_gauge_rel_std, kOpt);
    a->Visit("wheel_calibration", &wheel_calibration, kOpt);
    a->Visit("gyro_scale_std", &gyro_scale_std, kOpt);
    a->Visit("gyro_misalignment_std_deg", &gyro_misalignment_std_deg, kOpt);
    a->Visit("gyro_g_sensitivity_std_dps_per_g", &gyro_g_sensitivity_std_dps_per_g, kOpt);
    a->Visit("accel_scale_std", &accel_scale_std, kOpt);
    a->Visit("accel_misalignment_std_deg", &accel_misalignment_std_deg, kOpt);
    a->Visit("imu_mount_std_deg", &imu_mount_std_deg, kOpt);
    a->Visit("focal_length_rel_std", &focal_length_rel_std, kOpt);
    a->Visit("principal_point_std_px", &principal_point_std_px, kOpt);
    a->Visit("stereo_translation_std_mm", &stereo_translation_std_mm, kOpt);
    a->Visit("stereo_rotation_std_mrad", &stereo_rotation_std_mrad, kOpt);
    a->Visit("camera_mount_std_deg", &camera_mount_std_deg, kOpt);
    a->Visit("focal_length_calibration_rel_std", &focal_length_calibration_rel_std, kOpt);
    a->Visit("principal_point_calibration_std_px", &principal_point_calibration_std_px, kOpt);
    a->Visit("stereo_translation_calibration_std_mm", &stereo_translation_calibration_std_mm, kOpt);
    a->Visit("stereo_rotation_calibration_std_mrad", &stereo_rotation_calibration_std_mrad, kOpt);
    a->Visit("camera_mount_calibration_std_deg", &camera_mount_calibration_std_deg, kOpt);
    a->Visit("distortion_calibration_std", &distortion_calibration_std, kOpt);
    a->Visit("distortion_calibration_rms_px", &distortion_calibration_rms_px, kOpt);
    a->Visit("camera_time_offset_s", &camera_time_offset_s, kOpt);
  }
};

/// `stereo` with the camera's image effects the realism profile sets where the scenario
/// leaves them out (the lens, the rolling shutter; docs/camera_model.md).
StereoRigOptions WithCameraEffectsResolved(StereoRigOptions stereo, Realism profile);

/// The design as a calibration: both tracks at the design's sprocket radius, a perfect
/// IMU aligned with the body, the stereo rig's cameras with their lens (when `stereo` is
/// on; its effects resolved).
calibration::RobotCalibration DesignCalibration(const TrackedVehicleOptions& vehicle,
                                                const StereoRigOptions& stereo);

/// The robot as built: the design perturbed by `imperfections` (resolved), drawn from
/// `seed`. Every spread is drawn whatever its value, in a fixed order, so that one
/// imperfection turned off leaves the others' draws as they were; a zero spread leaves
/// its value exactly the design's.
calibration::RobotCalibration DrawAsBuilt(const calibration::RobotCalibration& design,
                                          const Imperfections& imperfections, std::uint64_t seed);

/// The camera calibration the software is given: the cameras as built with the
/// calibration errors drawn from `seed`; and the IMU's as the software assumes it (the
/// design's, with the true time offset, which Kalibr-style calibration estimates).
/// The vehicle's is the design's here; the runner replaces it by the calibration run's.
calibration::RobotCalibration DrawGivenCalibration(const calibration::RobotCalibration& truth,
                                                   const calibration::RobotCalibration& design,
                                                   const Imperfections& imperfections,
                                                   std::uint64_t seed);

}  // namespace trackbed::robot
