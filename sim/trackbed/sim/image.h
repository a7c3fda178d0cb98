// Images the renderer produces: 8-bit grayscale and metric depth, row-major,
// row 0 at the top (image convention, not OpenGL's).
#pragma once

#include <cstdint>
#include <vector>

namespace trackbed::sim {

struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< width * height, row-major, top row first.

  std::uint8_t at(int u, int v) const { return pixels[static_cast<std::size_t>(v) * width + u]; }
};

/// Depth along the camera's optical axis (z of the OpenCV camera frame) [m];
/// +infinity where the ray meets nothing (sky).
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth_m;

  float at(int u, int v) const { return depth_m[static_cast<std::size_t>(v) * width + u]; }
};

}  // namespace trackbed::sim
