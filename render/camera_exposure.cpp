// A camera's exposure as the mean of renders over it (see camera_exposure.h).
#include "trackbed/render/camera_exposure.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace trackbed::render {

Eigen::Isometry3d BodyMotion::PoseAfter(double dt_s) const {
  Eigen::Isometry3d T = T_world_body;
  const double angle = omega_world.norm() * dt_s;
  if (angle != 0.0) {
    T.linear() = Eigen::AngleAxisd(angle, omega_world.normalized()).toRotationMatrix() *
                 T_world_body.linear();
  }
  T.translation() += v_world * dt_s;
  return T;
}

CameraExposure::CameraExposure(const geometry::PinholeCamera& sensor,
                               const geometry::PinholeCamera& render, int samples,
                               double line_delay_s)
    : warp_(sensor, render), samples_(samples), line_delay_s_(line_delay_s) {
  if (samples < 1 || samples > 64) {
    throw std::invalid_argument("CameraExposure: samples must be in [1, 64] (got " +
                                std::to_string(samples) + ")");
  }
  if (!(std::isfinite(line_delay_s) && line_delay_s >= 0.0)) {
    throw std::invalid_argument("CameraExposure: line delay must be >= 0 s (got " +
                                std::to_string(line_delay_s) + ")");
  }
}

void CameraExposure::Render(Renderer& renderer, const BodyMotion& motion,
                            const Eigen::Isometry3d& T_body_camera, double t_s,
                            double exposure_time_s, GrayImage* gray,
                            const Eigen::Vector2d* detail_center_xy) {
  if (!(std::isfinite(exposure_time_s) && exposure_time_s >= 0.0)) {
    throw std::invalid_argument("CameraExposure: exposure time must be >= 0 s (got " +
                                std::to_string(exposure_time_s) + ")");
  }
  const Eigen::Isometry3d T_world_camera = motion.T_world_body * T_body_camera;
  const SensorTiming timing{exposure_time_s, samples(exposure_time_s), line_delay_s_};
  if (warp_.identity() && timing.instant()) {
    renderer.Render(warp_.render(), T_world_camera, t_s, gray, nullptr, detail_center_xy);
    return;
  }
  renderer.Render(warp_.render(), T_world_camera, t_s, &rendered_,
                  timing.instant() ? nullptr : &depth_, detail_center_xy);
  // The camera's coordinates at the render to its coordinates dt later.
  const CameraMotion camera_motion = [&](double dt) {
    return (motion.PoseAfter(dt) * T_body_camera).inverse() * T_world_camera;
  };
  warp_.Apply(rendered_, timing.instant() ? nullptr : &depth_, camera_motion, timing, gray);
}

}  // namespace trackbed::render
