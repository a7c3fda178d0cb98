// A camera's exposure as the mean of renders over it (see camera_exposure.h).
#include "trackbed/sim/camera_exposure.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace trackbed::sim {

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

CameraExposure::CameraExposure(double exposure_time_s, int samples)
    : exposure_time_s_(exposure_time_s), samples_(samples) {
  if (!(std::isfinite(exposure_time_s) && exposure_time_s >= 0.0)) {
    throw std::invalid_argument("CameraExposure: exposure time must be >= 0 s (got " +
                                std::to_string(exposure_time_s) + ")");
  }
  if (samples < 1 || samples > 64) {
    throw std::invalid_argument("CameraExposure: samples must be in [1, 64] (got " +
                                std::to_string(samples) + ")");
  }
}

void CameraExposure::Render(Renderer& renderer, const geometry::PinholeCamera& K,
                            const BodyMotion& motion, const Eigen::Isometry3d& T_body_camera,
                            double t_s, GrayImage* gray, const Eigen::Vector2d* detail_center_xy) {
  const int n = samples();
  if (n == 1) {
    renderer.Render(K, motion.T_world_body * T_body_camera, t_s, gray, nullptr, detail_center_xy);
    return;
  }
  for (int k = 0; k < n; ++k) {
    // Midpoint of the k-th of n equal parts of [−T/2, T/2].
    const double dt = exposure_time_s_ * ((k + 0.5) / n - 0.5);
    renderer.Render(K, motion.PoseAfter(dt) * T_body_camera, t_s + dt, &sub_, nullptr,
                    detail_center_xy);
    if (k == 0) sum_.assign(sub_.pixels.size(), 0);
    for (std::size_t i = 0; i < sub_.pixels.size(); ++i) sum_[i] += sub_.pixels[i];
  }
  gray->width = sub_.width;
  gray->height = sub_.height;
  gray->pixels.resize(sum_.size());
  const unsigned half = static_cast<unsigned>(n) / 2, count = static_cast<unsigned>(n);
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    gray->pixels[i] = static_cast<std::uint8_t>((sum_[i] + half) / count);
  }
}

}  // namespace trackbed::sim
