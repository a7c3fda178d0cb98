// A camera's exposure: one render of the scene at the frame's instant, warped into what
// the sensor records (render/sensor_warp.h): through its lens, each row at its own time
// under a rolling shutter, and integrated over the time the shutter is open, so that
// what moves across the view meanwhile is smeared (motion blur).
//
// A real camera does not take an instant: at 0.4 m/s in a 30°/s turn, a 10 ms
// exposure sweeps the view by 0.3°, 2 px at 381 px focal length. The renderer draws
// instants; the warp moves the render by the camera's motion over the exposure with the
// body moving at its velocity and angular velocity at t (taken as constant over the
// frame, a few milliseconds in which a tracked robot's motion hardly changes). Moving
// occluders are drawn where they are at t: the camera's motion blurs them, their own
// does not. Noise and gain (robot::ApplySensorModel) come after it.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/render/image.h"
#include "trackbed/render/pinhole.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/sensor_warp.h"

namespace trackbed::render {

/// The body's pose and velocities at an exposure's centre (world frame).
struct BodyMotion {
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();      ///< of the body frame's origin [m/s]
  Eigen::Vector3d omega_world = Eigen::Vector3d::Zero();  ///< angular velocity [rad/s]

  /// The body's pose `dt_s` after the centre, at constant velocities.
  Eigen::Isometry3d PoseAfter(double dt_s) const;
};

/// A camera's frames: renders with a shared renderer, warped for this camera. Holds the
/// render buffers and the warp, so that no frame allocates. Not copyable.
class CameraExposure {
 public:
  /// The camera `sensor` (with its lens), drawn through the pinhole `render` (the
  /// renderer's size: RenderCameraFor(sensor), grown to the renderer's size).
  /// `samples` in [1, 64] instants average an exposure; `line_delay_s` >= 0 (rolling
  /// shutter). Throws std::invalid_argument otherwise.
  CameraExposure(const geometry::PinholeCamera& sensor, const geometry::PinholeCamera& render,
                 int samples, double line_delay_s);
  CameraExposure(const CameraExposure&) = delete;
  CameraExposure& operator=(const CameraExposure&) = delete;

  const geometry::PinholeCamera& sensor() const { return warp_.sensor(); }
  double line_delay_s() const { return line_delay_s_; }
  /// Instants an exposure of `exposure_time_s` averages.
  int samples(double exposure_time_s) const { return exposure_time_s > 0.0 ? samples_ : 1; }

  /// The image of the camera at `T_body_camera` on a body moving as `motion`, its middle
  /// row exposed for `exposure_time_s` (>= 0) around `t_s`. `detail_center_xy` as for
  /// Renderer::Render. With an ideal lens, no rolling shutter and no exposure time, the
  /// render itself.
  void Render(Renderer& renderer, const BodyMotion& motion, const Eigen::Isometry3d& T_body_camera,
              double t_s, double exposure_time_s, GrayImage* gray,
              const Eigen::Vector2d* detail_center_xy = nullptr);

 private:
  SensorWarp warp_;
  int samples_;
  double line_delay_s_;
  GrayImage rendered_;
  DepthImage depth_;
};

}  // namespace trackbed::render
