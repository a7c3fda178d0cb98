// The pinhole camera's OpenGL projection (see pinhole.h).
//
// Derivation of OpenGlProjection: with X, Y, Z the OpenCV camera coordinates
// (X = x_gl, Y = −y_gl, Z = −z_gl), OpenGL puts the centre of window pixel
// column i at x_win = i + 0.5 and of window row j (bottom-up) at y_win = j + 0.5;
// the image row is v = H − 1 − j. Requiring x_win = u + 0.5 with u = fx X/Z + cx
// and y_win = H − (v + 0.5) with v = fy Y/Z + cy gives
//   x_ndc = 2 fx/W · X/Z + 2 (cx + 0.5)/W − 1,
//   y_ndc = −2 fy/H · Y/Z + 1 − 2 (cy + 0.5)/H,
// which, multiplied by w_clip = Z = −z_gl, are the first two rows below.
#include "trackbed/render/pinhole.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace trackbed::render {

Eigen::Matrix4d OpenGlProjection(const geometry::PinholeCamera& K, double near_m, double far_m) {
  if (!K.distortion.is_zero()) {
    throw std::invalid_argument(
        "OpenGlProjection: rasterises an ideal pinhole; a lens with "
        "distortion must be applied to the rendered image");
  }
  const double w = K.width_px, h = K.height_px;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2.0 * K.fx / w;
  P(0, 2) = 1.0 - 2.0 * (K.cx + 0.5) / w;
  P(1, 1) = 2.0 * K.fy / h;
  P(1, 2) = 2.0 * (K.cy + 0.5) / h - 1.0;
  P(2, 2) = -(far_m + near_m) / (far_m - near_m);
  P(2, 3) = -2.0 * far_m * near_m / (far_m - near_m);
  P(3, 2) = -1.0;
  return P;
}

double DepthFromBuffer(double d, double near_m, double far_m) {
  if (d >= 1.0) return std::numeric_limits<double>::infinity();
  const double z_ndc = 2.0 * d - 1.0;
  return 2.0 * far_m * near_m / ((far_m + near_m) - z_ndc * (far_m - near_m));
}

}  // namespace trackbed::render
