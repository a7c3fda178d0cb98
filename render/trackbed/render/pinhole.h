// The OpenGL side of the shared pinhole camera (common/pinhole_camera.h): the
// projection matrix that rasterises exactly like it, and metric depth from the depth
// buffer. OpenCV conventions: camera x right, y down, z forward; pixel (u, v) = (0, 0)
// is the centre of the top-left pixel.
#pragma once

#include <Eigen/Core>

#include "trackbed/common/pinhole_camera.h"

namespace trackbed::render {

/// The OpenGL projection matrix (column vectors, OpenGL eye coordinates: x right, y up,
/// z backward) that rasterises exactly like `K`'s ideal pinhole: a point projecting to
/// pixel (u, v) lands on the centre of pixel column u, row v (top-down) of the
/// read-back image, with depth clipped to [near_m, far_m]. Throws std::invalid_argument
/// for a camera with lens distortion (a rasteriser draws straight lines straight).
Eigen::Matrix4d OpenGlProjection(const geometry::PinholeCamera& K, double near_m, double far_m);

/// Metric depth along the optical axis from an OpenGL depth-buffer value d in [0, 1]
/// written with OpenGlProjection(K, near_m, far_m). d = 1 (nothing drawn) gives +infinity.
double DepthFromBuffer(double d, double near_m, double far_m);

}  // namespace trackbed::render
