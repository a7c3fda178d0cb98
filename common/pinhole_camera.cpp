// Pinhole camera and its lens (see pinhole_camera.h).
#include "trackbed/common/pinhole_camera.h"

#include <cmath>

#include <Eigen/LU>
#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::geometry {

namespace {

// Radial–tangential: the distorted point and its Jacobian at undistorted (x, y).
Eigen::Vector2d RadTan(const LensDistortion& d, const Eigen::Vector2d& xy, Eigen::Matrix2d* J) {
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  const double dradial = d.k1 + r2 * (2.0 * d.k2 + 3.0 * r2 * d.k3);  // ∂radial/∂r²
  if (J) {
    (*J)(0, 0) = radial + 2.0 * x * x * dradial + 2.0 * d.p1 * y + 6.0 * d.p2 * x;
    (*J)(0, 1) = 2.0 * x * y * dradial + 2.0 * d.p1 * x + 2.0 * d.p2 * y;
    (*J)(1, 0) = (*J)(0, 1);
    (*J)(1, 1) = radial + 2.0 * y * y * dradial + 6.0 * d.p1 * y + 2.0 * d.p2 * x;
  }
  return {x * radial + 2.0 * d.p1 * x * y + d.p2 * (r2 + 2.0 * x * x),
          y * radial + d.p1 * (r2 + 2.0 * y * y) + 2.0 * d.p2 * x * y};
}

// Equidistant: θ_d of θ, and its derivative.
double ThetaD(const LensDistortion& d, double theta, double* dtheta_d) {
  const double t2 = theta * theta;
  const double poly = 1.0 + t2 * (d.k1 + t2 * (d.k2 + t2 * (d.k3 + t2 * d.k4)));
  if (dtheta_d) {
    *dtheta_d = 1.0 + t2 * (3.0 * d.k1 + t2 * (5.0 * d.k2 + t2 * (7.0 * d.k3 + t2 * 9.0 * d.k4)));
  }
  return theta * poly;
}

}  // namespace

LensDistortion LensDistortion::RadialTangential(double k1, double k2, double p1, double p2,
                                                double k3) {
  LensDistortion d;
  d.model = LensModel::kRadialTangential;
  d.k1 = k1, d.k2 = k2, d.k3 = k3, d.p1 = p1, d.p2 = p2;
  return d;
}

LensDistortion LensDistortion::Equidistant(double k1, double k2, double k3, double k4) {
  LensDistortion d;
  d.model = LensModel::kEquidistant;
  d.k1 = k1, d.k2 = k2, d.k3 = k3, d.k4 = k4;
  return d;
}

bool LensDistortion::is_zero() const {
  return model == LensModel::kNone || (model == LensModel::kRadialTangential && k1 == 0.0 &&
                                       k2 == 0.0 && k3 == 0.0 && p1 == 0.0 && p2 == 0.0);
}

Eigen::Vector2d LensDistortion::Distort(const Eigen::Vector2d& xy) const {
  switch (model) {
    case LensModel::kNone:
      return xy;
    case LensModel::kRadialTangential:
      return RadTan(*this, xy, nullptr);
    case LensModel::kEquidistant: {
      const double r = xy.norm();
      if (r < 1e-12) return xy;
      return xy * (ThetaD(*this, std::atan(r), nullptr) / r);
    }
  }
  return xy;
}

Eigen::Vector2d LensDistortion::Undistort(const Eigen::Vector2d& xy_d) const {
  if (model == LensModel::kNone) return xy_d;
  if (model == LensModel::kEquidistant) {
    // θ from θ_d along the same ray, then r = tan θ.
    const double rd = xy_d.norm();
    if (rd < 1e-12) return xy_d;
    double theta = rd;
    for (int i = 0; i < 50; ++i) {
      double slope = 0.0;
      const double step = (ThetaD(*this, theta, &slope) - rd) / slope;
      theta -= step;
      if (std::abs(step) < 1e-14) break;
    }
    return xy_d * (std::tan(theta) / rd);
  }
  Eigen::Vector2d xy = xy_d;
  for (int i = 0; i < 50; ++i) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d residual = RadTan(*this, xy, &J) - xy_d;
    const Eigen::Vector2d delta = J.partialPivLu().solve(residual);
    xy -= delta;
    if (delta.norm() < 1e-14) break;
  }
  return xy;
}

void LensDistortion::Validate() const {
  option_check::Finite("k1", k1);
  option_check::Finite("k2", k2);
  option_check::Finite("k3", k3);
  option_check::Finite("k4", k4);
  option_check::Finite("p1", p1);
  option_check::Finite("p2", p2);
  if (model == LensModel::kNone &&
      !(k1 == 0 && k2 == 0 && k3 == 0 && k4 == 0 && p1 == 0 && p2 == 0)) {
    throw OptionError("model", "is none, but coefficients are set");
  }
  if (model == LensModel::kRadialTangential && k4 != 0.0) {
    throw OptionError("k4", "is an equidistant coefficient (model is radial_tangential)");
  }
  if (model == LensModel::kEquidistant && (p1 != 0.0 || p2 != 0.0)) {
    throw OptionError(p1 != 0.0 ? "p1" : "p2",
                      "is a radial_tangential coefficient (model is equidistant)");
  }
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
