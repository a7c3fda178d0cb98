// The stereo camera rig on the chassis: two identical pinhole cameras, the
// right one displaced by the baseline along the left camera's x axis
// (rectified pair), plus the camera's sensor model (exposure, noise).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/common/archive.h"
#include "trackbed/common/robot_calibration.h"
#include "trackbed/common/stereo_camera.h"
#include "trackbed/render/image.h"
#include "trackbed/render/pinhole.h"
#include "trackbed/robot/auto_exposure.h"
#include "trackbed/robot/image_sensor.h"

namespace trackbed::robot {

/// `robot.stereo.rolling_shutter`: rows exposed one after another (render/sensor_warp.h).
struct RollingShutterOptions {
  /// Delay from one row's exposure to the next's [s], >= 0; 0 is a global shutter.
  /// Absent: the realism profile's (docs/camera_model.md).
  std::optional<double> line_delay_s;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("line_delay_s", &line_delay_s, archive::kOmitEmpty);
  }
};

struct StereoRigOptions {
  /// Whether the robot carries (and the run renders) the stereo camera.
  bool enabled = false;
  /// Image size [px].
  int width_px = 640;
  int height_px = 480;
  /// Horizontal field of view [deg], in (10, 170).
  double hfov_deg = 80.0;
  /// Focal length [px] (square pixels), > 0: when set it replaces hfov_deg's, to give a
  /// published camera's calibration (KITTI's, for the twin).
  std::optional<double> focal_length_px;
  /// Principal point (cx, cy) [px], the centre of the top-left pixel at (0, 0); absent:
  /// the image's centre ((width − 1) / 2, (height − 1) / 2).
  std::optional<Eigen::Vector2d> principal_point_px;
  /// Distance between the two optical centres [m], > 0.
  double baseline_m = 0.12;
  /// Midpoint between the optical centres in the body frame [m] (x forward, y
  /// left, z up from the centre of mass, which is 0.20 m above flat ground: the
  /// default puts the cameras 0.50 m above the ground).
  Eigen::Vector3d mount_m{0.25, 0.0, 0.30};
  /// Downward tilt of the optical axes [deg], in [-45, 60].
  double pitch_down_deg = 5.0;
  /// Frame rate [Hz], > 0.
  double rate_hz = 10.0;
  /// Rendering clip distances [m], 0 < near < far.
  double near_m = 0.05;
  double far_m = 120.0;
  /// Exposure gain applied to the rendered radiance [-], > 0.
  double exposure = 1.0;
  /// Standard deviation of the sensor's additive noise [grey levels], >= 0.
  double noise_std = 1.0;
  /// How long the shutter is open [s], in [0, 1 / rate_hz]: what moves across the
  /// view meanwhile is smeared (render/camera_exposure.h). 0 takes an instant.
  double exposure_time_s = 0.0;
  /// Instants of the render's warp averaged over an exposure, in [1, 64] (used when
  /// the exposure time is > 0).
  int exposure_samples = 4;
  /// Both cameras' lens as designed (as built: the same; the calibration given to the
  /// software: drawn about it). Absent: the realism profile's (docs/camera_model.md).
  std::optional<geometry::LensDistortion> distortion;
  RollingShutterOptions rolling_shutter;
  /// The sensor in electrons (robot/image_sensor.h); when enabled it replaces
  /// `noise_std`'s grey-level noise.
  PhotometricOptions photometric;
  /// Exposure time and gain set frame by frame (robot/auto_exposure.h); the render shows
  /// the scene at `exposure_time_s`, the controller's first exposure.
  AutoExposureOptions auto_exposure;
  /// Render pixels per image pixel along each axis, in [1, 4]: above 1 each pixel is
  /// the mean over its area instead of one point of the scene (antialiasing), at
  /// `supersampling`² times the pixels to draw (docs/camera_model.md).
  int supersampling = 1;
  /// Samples per render pixel at the edges of drawn geometry, 1 or 4: with 4 each pixel
  /// an edge crosses shows the mean of its four samples, the light of both sides by
  /// about the fraction each covers, as a pixel integrates light over its area
  /// (docs/rendering.md, "Antialiased edges"); 1 draws one sample at the centre.
  int edge_antialiasing_samples = 1;
  /// Camera faults: [start, duration] pairs [s] during which both cameras deliver black
  /// frames (a covered lens, a dropped link), for fault tests.
  std::vector<Eigen::Vector2d> blackouts_s;

  /// Whether time `t_s` falls in a blackout.
  bool InBlackout(double t_s) const;
  /// Each camera's intrinsics as designed: the image size, the focal length (given, or
  /// from hfov_deg) and the principal point (given, or the centre); no lens.
  geometry::PinholeCamera DesignIntrinsics() const;
  /// Throws OptionError naming the first invalid key (a lens that does not reach every
  /// pixel of the image, or sees more than 160° across, is `distortion`).
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("enabled", &enabled);
    a->Visit("width_px", &width_px);
    a->Visit("height_px", &height_px);
    a->Visit("hfov_deg", &hfov_deg);
    a->Visit("focal_length_px", &focal_length_px, archive::kOmitEmpty);
    a->Visit("principal_point_px", &principal_point_px, archive::kOmitEmpty);
    a->Visit("baseline_m", &baseline_m);
    a->Visit("mount_m", &mount_m);
    a->Visit("pitch_down_deg", &pitch_down_deg);
    a->Visit("rate_hz", &rate_hz);
    a->Visit("near_m", &near_m);
    a->Visit("far_m", &far_m);
    a->Visit("exposure", &exposure);
    a->Visit("noise_std", &noise_std);
    a->Visit("exposure_time_s", &exposure_time_s);
    a->Visit("exposure_samples", &exposure_samples);
    a->Visit("blackouts_s", &blackouts_s);
    a->Visit("supersampling", &supersampling);
    a->Visit("edge_antialiasing_samples", &edge_antialiasing_samples);
    a->Visit("distortion", &distortion, archive::kOmitEmpty);
    a->Visit("rolling_shutter", &rolling_shutter);
    a->Visit("photometric", &photometric);
    a->Visit("auto_exposure", &auto_exposure);
  }

 private:
  void ValidateLensCoversTheImage() const;
};

/// Geometry of the rig; immutable.
class StereoRig {
 public:
  /// The rig as designed: a rectified pair.
  explicit StereoRig(const StereoRigOptions& options);
  /// The rig as built (robot/as_built.h): each camera's intrinsics and pose on the body.
  StereoRig(const StereoRigOptions& options, const calibration::StereoCalibration& as_built);

  const StereoRigOptions& options() const { return options_; }
  /// Intrinsics of the left camera (of both, as designed).
  const geometry::PinholeCamera& intrinsics() const { return intrinsics_; }
  /// Intrinsics of the right camera.
  const geometry::PinholeCamera& right_intrinsics() const { return right_intrinsics_; }
  /// The rectified pair as designed: the intrinsics and `options().baseline_m`.
  geometry::StereoCamera stereo_camera() const { return {intrinsics_, options_.baseline_m}; }
  /// Left / right camera (OpenCV axes: x right, y down, z forward) in the body frame.
  const Eigen::Isometry3d& T_body_left() const { return T_body_left_; }
  const Eigen::Isometry3d& T_body_right() const { return T_body_right_; }

 private:
  StereoRigOptions options_;
  geometry::PinholeCamera intrinsics_, right_intrinsics_;
  Eigen::Isometry3d T_body_left_, T_body_right_;
};

/// The camera's sensor: grey = clamp(round(exposure · radiance + noise)), noise
/// near-Gaussian with `noise_std` grey levels, drawn from a generator keyed by
/// (seed, frame, camera) so every image is reproducible on its own.
void ApplySensorModel(double exposure, double noise_std, std::uint64_t seed, std::uint64_t frame,
                      int camera, GrayImage* image);

}  // namespace trackbed::robot
