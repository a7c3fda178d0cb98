// The pinhole camera model shared by the renderer and everything that reads
// its images. OpenCV conventions: camera x right, y down, z forward; pixel
// (u, v) = (0, 0) is the centre of the top-left pixel.
#pragma once

#include <Eigen/Core>

namespace trackbed::sim {

struct PinholeIntrinsics {
  int width_px = 640;
  int height_px = 480;
  double fx = 381.4;  ///< Focal lengths [px].
  double fy = 381.4;
  double cx = 319.5;  ///< Principal point [px] (centre of a 640 × 480 image).
  double cy = 239.5;

  /// Pixel of a point in camera coordinates (z > 0).
  Eigen::Vector2d Project(const Eigen::Vector3d& p_camera) const {
    return {fx * p_camera.x() / p_camera.z() + cx, fy * p_camera.y() / p_camera.z() + cy};
  }

  /// Square pixels, principal point at the image centre, horizontal field of view `hfov_rad`.
  static PinholeIntrinsics FromFieldOfView(int width_px, int height_px, double hfov_rad);
};

/// The OpenGL projection matrix (column vectors, OpenGL eye coordinates: x right, y up,
/// z backward) that rasterises exactly like `K`: a point projecting to pixel (u, v) lands
/// on the centre of pixel column u, row v (top-down) of the read-back image, with depth
/// clipped to [near_m, far_m].
Eigen::Matrix4d OpenGlProjection(const PinholeIntrinsics& K, double near_m, double far_m);

/// Metric depth along the optical axis from an OpenGL depth-buffer value d in [0, 1]
/// written with OpenGlProjection(K, near_m, far_m). d = 1 (nothing drawn) gives +infinity.
double DepthFromBuffer(double d, double near_m, double far_m);

}  // namespace trackbed::sim
