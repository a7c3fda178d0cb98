// The robot's stereo camera as a device: the rig as built, one renderer for both
// cameras, each camera's exposure (lens, rolling shutter, motion blur:
// render/camera_exposure.h), the image sensors (robot/image_sensor.h, or the grey-level
// model of stereo_rig.h), the auto-exposure (robot/auto_exposure.h) and the blackout
// fault: from the body's motion at a frame's time to the pair of images the robot's
// software receives (docs/camera_model.md).
//
// Not common's geometry::StereoCamera (trackbed/common/stereo_camera.h), the rectified
// pair's geometry that the software computes with: this one is the simulated hardware.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/common/robot_calibration.h"
#include "trackbed/render/camera_exposure.h"
#include "trackbed/render/image.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/auto_exposure.h"
#include "trackbed/robot/image_sensor.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/sim/occluder.h"
#include "trackbed/sim/track_marks.h"
#include "trackbed/sim/world.h"

namespace trackbed::robot {

/// The camera's random streams (each a seed of its own, split_mix::Stream of the run's).
struct StereoCameraSeeds {
  std::uint64_t scene = 0;    ///< the renderer's: textures, occluders
  std::uint64_t noise = 0;    ///< the sensor's noise, keyed further by frame and camera
  std::uint64_t pattern = 0;  ///< the image sensors' fixed pattern (PRNU, DSNU)
};

/// One stereo frame as the camera took it: its stamp and settings, where each camera
/// truly was, and the pair's buffers.
struct StereoCapture {
  std::int64_t index = 0;  ///< 0, 1, 2, … in the order the frames were taken
  double t_s = 0.0;        ///< the stamp [s]; exposed `time_offset_s` later (as built)
  /// Ground truth of each camera at the exposure (OpenCV axes).
  Eigen::Isometry3d T_world_left = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_world_right = Eigen::Isometry3d::Identity();
  double exposure_time_s = 0.0;  ///< how long each row's shutter was open [s]
  double gain = 1.0;             ///< the analog gain the auto-exposure set (1 without it)
  bool blackout = false;         ///< a camera fault blanks this pair (blackouts_s)
  /// The light on the sensor relative to the render's (1 when the renderer applied it).
  double sensor_exposure = 1.0;
  /// The render was exposed before its 8 bits clipped (scene lighting).
  bool clipped_render = false;
  GrayImage* left = nullptr;  ///< the pair: the buffers given to Expose, or the camera's
  GrayImage* right = nullptr;
};

/// The stereo camera on the body. Holds the renderer, the render buffers and the
/// sensors, so that no frame allocates. Not copyable; keep the world alive while it is.
class StereoCamera {
 public:
  /// `options` with the camera effects resolved (WithCameraEffectsResolved), the rig as
  /// built `as_built`, its pairs exposed `time_offset_s` after their stamp (as built, on
  /// the IMU's clock), the scene drawn as `appearance` with `occluders`. Throws
  /// OptionError or std::invalid_argument for bad options, std::runtime_error when
  /// OSMesa cannot make a context.
  StereoCamera(const StereoRigOptions& options, const calibration::StereoCalibration& as_built,
               double time_offset_s, const sim::World& world,
               const render::SceneAppearance& appearance, std::vector<sim::OccluderSpec> occluders,
               const StereoCameraSeeds& seeds);
  ~StereoCamera();
  StereoCamera(const StereoCamera&) = delete;
  StereoCamera& operator=(const StereoCamera&) = delete;

  const StereoRig& rig() const { return rig_; }
  /// Frames taken so far.
  std::int64_t frames() const { return frames_; }
  bool has_auto_exposure() const { return auto_exposure_.has_value(); }

  /// The boxes of the body (its frame) whose shadow the sun casts in the images when
  /// the scene's appearance asks for it (render::Renderer::SetRobotShape).
  void SetBodyShape(std::vector<render::ShadowBox> boxes_body);
  /// The robot's track marks to draw over the ground (render::Renderer::SetTrackMarks).
  void SetTrackMarks(const sim::TrackMarks* marks);

  /// The pair stamped `t_s`, the body moving as `body` then: Expose, then Finish.
  StereoCapture Capture(double t_s, const render::BodyMotion& body, GrayImage* left = nullptr,
                        GrayImage* right = nullptr);

  /// The pair stamped `t_s` rendered into `left`, `right` (or, when null, the camera's
  /// own pair, valid until the next frame): through the lens, row by row under a rolling
  /// shutter, over the exposure time and pre-exposed as the auto-exposure sets it; the
  /// sensor is still to come (Finish or Develop).
  StereoCapture Expose(double t_s, const render::BodyMotion& body, GrayImage* left = nullptr,
                       GrayImage* right = nullptr);
  /// The sensor on an exposed pair (Develop), then the auto-exposure meters its left
  /// image for the next frame (not in a blackout).
  void Finish(const StereoCapture& capture);
  /// The sensor model (exposure, gain, noise keyed by seed, frame and camera), then the
  /// blackout, on an exposed pair in place. Reads only what construction fixed, so it
  /// may run on another thread while this one exposes the next frames; without the
  /// auto-exposure it is all that Finish does.
  void Develop(const StereoCapture& capture) const;

 private:
  StereoRig rig_;
  double time_offset_s_;
  std::uint64_t noise_seed_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::CameraExposure> exposures_[2];  // left, right
  std::vector<ImageSensor> image_sensors_;                // left, right; or none
  std::optional<AutoExposure> auto_exposure_;             // when on
  GrayImage left_, right_;                                // the camera's own pair
  std::int64_t frames_ = 0;
};

}  // namespace trackbed::robot
