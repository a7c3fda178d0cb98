// A camera's exposure: the image integrated over the time the shutter is open,
// so that what moves across the view during it is smeared (motion blur).
//
// A real camera does not take an instant: at 0.4 m/s in a 30°/s turn, a 10 ms
// exposure sweeps the view by 0.3°, 2 px at 381 px focal length. The renderer
// draws instants, so an exposure of duration T centred at t is approximated by
// the mean of N renders at the midpoints of N equal parts of [t − T/2, t + T/2],
// with the body moving at its velocity and angular velocity at t (taken as
// constant over T, a few milliseconds in which a tracked robot's motion hardly
// changes) and the scene's occluders at each instant. The mean of the renders'
// grey levels is rounded to grey levels once; noise and gain
// (robot::ApplySensorModel) come after it. T = 0 is one render at t.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/sim/image.h"
#include "trackbed/sim/pinhole.h"
#include "trackbed/sim/renderer.h"

namespace trackbed::sim {

/// The body's pose and velocities at an exposure's centre (world frame).
struct BodyMotion {
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();      ///< of the body frame's origin [m/s]
  Eigen::Vector3d omega_world = Eigen::Vector3d::Zero();  ///< angular velocity [rad/s]

  /// The body's pose `dt_s` after the centre, at constant velocities.
  Eigen::Isometry3d PoseAfter(double dt_s) const;
};

/// Renders exposures with one renderer; holds the sum and sub-frame buffers so that
/// no frame allocates. Not copyable.
class CameraExposure {
 public:
  /// `exposure_time_s` >= 0, `samples` in [1, 64] (used when the time is > 0).
  /// Throws std::invalid_argument otherwise.
  CameraExposure(double exposure_time_s, int samples);
  CameraExposure(const CameraExposure&) = delete;
  CameraExposure& operator=(const CameraExposure&) = delete;

  double exposure_time_s() const { return exposure_time_s_; }
  int samples() const { return exposure_time_s_ > 0.0 ? samples_ : 1; }

  /// The image of the camera at `T_body_camera` on a body moving as `motion`,
  /// exposed around `t_s`. `detail_center_xy` as for Renderer::Render (held for
  /// the whole exposure, so the terrain's meshes do not change within it).
  void Render(Renderer& renderer, const geometry::PinholeCamera& K, const BodyMotion& motion,
              const Eigen::Isometry3d& T_body_camera, double t_s, GrayImage* gray,
              const Eigen::Vector2d* detail_center_xy = nullptr);

 private:
  double exposure_time_s_;
  int samples_;
  GrayImage sub_;
  std::vector<std::uint16_t> sum_;
};

}  // namespace trackbed::sim
