// Pinhole camera and radial–tangential lens (see pinhole_camera.h).
#include "trackbed/common/pinhole_camera.h"

#include <cmath>
#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::geometry {

namespace {

/// The model's two parts at undistorted (x, y): the radial factor and the tangential
/// offset, x_d = x·radial + tangential.
struct LensTerms {
  double radial;
  Eigen::Vector2d tangential;
};

LensTerms TermsAt(const RadialTangential& d, const Eigen::Vector2d& xy) {
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  return {1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3)),
          {2.0 * d.p1 * x * y + d.p2 * (r2 + 2.0 * x * x),
           d.p1 * (r2 + 2.0 * y * y) + 2.0 * d.p2 * x * y}};
}

}  // namespace

Eigen::Vector2d RadialTangential::Distort(const Eigen::Vector2d& xy) const {
  const LensTerms t = TermsAt(*this, xy);
  return xy * t.radial + t.tangential;
}

Eigen::Vector2d RadialTangential::Undistort(const Eigen::Vector2d& xy_d) const {
  Eigen::Vector2d xy = xy_d;
  for (int i = 0; i < 50; ++i) {
    const LensTerms t = TermsAt(*this, xy);
    const Eigen::Vector2d next = (xy_d - t.tangential) / t.radial;
    const double step = (next - xy).norm();
    xy = next;
    if (step < 1e-12) break;
  }
  return xy;
}

Eigen::Vector2d PinholeCamera::Project(const Eigen::Vector3d& p_camera) const {
  if (distortion.is_zero()) {
    return {fx * p_camera.x() / p_camera.z() + cx, fy * p_camera.y() / p_camera.z() + cy};
  }
  const Eigen::Vector2d d = distortion.Distort(p_camera.head<2>() / p_camera.z());
  return {fx * d.x() + cx, fy * d.y() + cy};
}

Eigen::Vector3d PinholeCamera::Backproject(double u, double v, double z) const {
  Eigen::Vector2d xy((u - cx) / fx, (v - cy) / fy);
  if (!distortion.is_zero()) xy = distortion.Undistort(xy);
  return {xy.x() * z, xy.y() * z, z};
}

Eigen::Matrix3d PinholeCamera::K() const {
  Eigen::Matrix3d K;
  K << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return K;
}

void PinholeCamera::Validate() const {
  if (width_px <= 0) {
    throw OptionError("width_px", "must be > 0 (got " + std::to_string(width_px) + ")");
  }
  if (height_px <= 0) {
    throw OptionError("height_px", "must be > 0 (got " + std::to_string(height_px) + ")");
  }
  option_check::Positive("fx", fx);
  option_check::Positive("fy", fy);
  option_check::Finite("cx", cx);
  option_check::Finite("cy", cy);
}

PinholeCamera PinholeCamera::FromFieldOfView(int width_px, int height_px, double hfov_rad) {
  PinholeCamera K;
  K.width_px = width_px;
  K.height_px = height_px;
  K.fx = K.fy = 0.5 * width_px / std::tan(0.5 * hfov_rad);
  K.cx = 0.5 * (width_px - 1);
  K.cy = 0.5 * (height_px - 1);
  return K;
}

}  // namespace trackbed::geometry
