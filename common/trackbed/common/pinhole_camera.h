// The camera vocabulary every library shares: one pinhole camera (with its lens
// distortion) and one rectified stereo pair. OpenCV conventions: camera x right,
// y down, z forward; pixel (u, v) = (0, 0) is the centre of the top-left pixel.
#pragma once

#include <Eigen/Core>

namespace trackbed::geometry {

/// Radial–tangential lens distortion (Brown 1966, Conrady 1919), the model of OpenCV's
/// `k1, k2, p1, p2, k3` and of Bouguet's calibration toolbox. It maps undistorted
/// normalized image coordinates (x, y) = (X/Z, Y/Z) to distorted ones:
///   r² = x² + y²,  radial = 1 + k1 r² + k2 r⁴ + k3 r⁶,
///   x_d = x·radial + 2 p1 x y + p2 (r² + 2x²),
///   y_d = y·radial + p1 (r² + 2y²) + 2 p2 x y.
/// All zero (the default) is an ideal pinhole.
struct RadialTangential {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0;  ///< radial coefficients
  double p1 = 0.0, p2 = 0.0;            ///< tangential (decentring) coefficients

  bool is_zero() const { return k1 == 0.0 && k2 == 0.0 && k3 == 0.0 && p1 == 0.0 && p2 == 0.0; }
  /// Distorted normalized coordinates of undistorted `xy`.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xy) const;
  /// Undistorted normalized coordinates of distorted `xy_d`: the fixed-point iteration
  /// OpenCV's undistortPoints uses, until the step is below 1e-12 or 50 iterations.
  Eigen::Vector2d Undistort(const Eigen::Vector2d& xy_d) const;
};

/// A pinhole camera: image size, focal lengths and principal point [px], and its lens.
struct PinholeCamera {
  int width_px = 0;
  int height_px = 0;
  double fx = 0.0;  ///< focal lengths [px], > 0
  double fy = 0.0;
  double cx = 0.0;  ///< principal point [px], finite
  double cy = 0.0;
  RadialTangential distortion;  ///< zero: an ideal pinhole

  /// Pixel of a point in camera coordinates (z > 0), through the lens.
  Eigen::Vector2d Project(const Eigen::Vector3d& p_camera) const;
  /// The point at depth z [m] along the optical axis that projects to pixel (u, v);
  /// undistorts first when the lens is not ideal.
  Eigen::Vector3d Backproject(double u, double v, double z) const;
  /// The intrinsic matrix K = [fx 0 cx; 0 fy cy; 0 0 1].
  Eigen::Matrix3d K() const;

  /// Throws OptionError naming the first invalid field (width_px, height_px > 0;
  /// fx, fy > 0 and finite; cx, cy finite).
  void Validate() const;

  /// Square pixels, principal point at the image centre, horizontal field of view
  /// `hfov_rad`, no distortion.
  static PinholeCamera FromFieldOfView(int width_px, int height_px, double hfov_rad);
};

}  // namespace trackbed::geometry
