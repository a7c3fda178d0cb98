// OpenCV views of the shared vocabulary: a grey image as a cv::Mat without a copy,
// and a pinhole camera's matrix and size in OpenCV's types.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "trackbed/common/gray_image.h"
#include "trackbed/common/pinhole_camera.h"

namespace trackbed::perception {

/// A CV_8UC1 header over `image`'s pixels (no copy), valid while `image` lives and is
/// not resized. OpenCV has no read-only Mat: the caller must not write through it.
inline cv::Mat AsCvMat(const GrayImage& image) {
  return cv::Mat(image.height, image.width, CV_8UC1,
                 const_cast<std::uint8_t*>(image.pixels.data()));
}

/// Throws std::invalid_argument, naming `function`, unless `gray` is a non-empty
/// CV_8UC1 image.
inline void CheckGray8(const cv::Mat& gray, const char* function) {
  if (gray.empty() || gray.type() != CV_8UC1) {
    throw std::invalid_argument(std::string(function) + ": needs a non-empty CV_8UC1 image");
  }
}

/// The camera matrix K of `camera`.
inline cv::Matx33d CvCameraMatrix(const geometry::PinholeCamera& camera) {
  return {camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0};
}

/// The image size of `camera`.
inline cv::Size CvImageSize(const geometry::PinholeCamera& camera) {
  return {camera.width_px, camera.height_px};
}

}  // namespace trackbed::perception
