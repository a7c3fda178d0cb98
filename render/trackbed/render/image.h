// Images the renderer produces: 8-bit grayscale (the shared GrayImage) and metric
// depth, row-major, row 0 at the top (image convention, not OpenGL's).
#pragma once

#include <cstdint>
#include <vector>

#include "trackbed/common/gray_image.h"

namespace trackbed::render {

/// Depth along the camera's optical axis (z of the OpenCV camera frame) [m];
/// +infinity where the ray meets nothing (sky).
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth_m;

  float at(int u, int v) const { return depth_m[static_cast<std::size_t>(v) * width + u]; }
};

}  // namespace trackbed::render
