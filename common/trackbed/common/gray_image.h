// An 8-bit grey image, the one image type the renderer writes, the camera model
// degrades and the stack reads (through perception/opencv_views.h as a cv::Mat).
#pragma once

#include <cstdint>
#include <vector>

namespace trackbed {

struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< width * height, row-major, top row first.

  std::uint8_t at(int u, int v) const { return pixels[static_cast<std::size_t>(v) * width + u]; }
};

}  // namespace trackbed
