// A rectified stereo pair: both cameras share one pinhole model and the right one sits
// `baseline_m` along the left camera's +x axis (OpenCV axes, see pinhole_camera.h).
// Also the KITTI form of its calibration, P0 = K [I | 0] and P1 = K [I | (−fx·b, 0, 0)ᵀ].
#pragma once

#include <Eigen/Core>

#include "trackbed/common/pinhole_camera.h"

namespace trackbed::geometry {

struct StereoCamera {
  PinholeCamera left;       ///< the rectified left camera; the right shares it
  double baseline_m = 0.0;  ///< [m], > 0

  /// Point in the left camera frame [m] from a left pixel (u, v) [px] and disparity
  /// d = u_left − u_right [px] > 0: Z = fx·b/d, X = (u − cx)·Z/fx, Y = (v − cy)·Z/fy.
  Eigen::Vector3d Triangulate(double u, double v, double disparity_px) const;
  /// Projection of a point p (left camera frame, Z > 0) into the pair:
  /// (u_left, v, u_right) [px], u_right = fx·(X − b)/Z + cx.
  Eigen::Vector3d Project(const Eigen::Vector3d& p) const;

  /// KITTI's P0 (left) and P1 (right) 3×4 projection matrices.
  Eigen::Matrix<double, 3, 4> LeftProjection() const;
  Eigen::Matrix<double, 3, 4> RightProjection() const;

  /// Throws OptionError naming the first invalid field: the left camera's
  /// (PinholeCamera::Validate, as `left.<field>`), then baseline_m > 0.
  void Validate() const;

  /// From KITTI-form projections: intrinsics from P0, baseline −P1(0,3) / P1(0,0); the
  /// image size is left 0 for the caller. Does not check the form (the KITTI reader
  /// does, with file and line).
  static StereoCamera FromProjections(const Eigen::Matrix<double, 3, 4>& P0,
                                      const Eigen::Matrix<double, 3, 4>& P1);
};

}  // namespace trackbed::geometry
