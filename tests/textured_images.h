// Textured test images shared by the image tests (the tracker's, the image statistics').
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace trackbed::testing_images {

/// Random texture with detail at two scales (uniform noise blurred with σ = 1.5 px plus
/// noise blurred with σ = 6 px, so that the coarse pyramid levels see texture too), full
/// 0..255 range, as float so that it can be resampled before quantisation.
inline cv::Mat Texture(int width, int height, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat fine(height, width, CV_32F), coarse(height, width, CV_32F);
  rng.fill(fine, cv::RNG::UNIFORM, 0.0, 1.0);
  rng.fill(coarse, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(fine, fine, cv::Size(0, 0), 1.5);
  cv::GaussianBlur(coarse, coarse, cv::Size(0, 0), 6.0);
  cv::Mat texture;
  cv::normalize(fine, fine, 0.0, 1.0, cv::NORM_MINMAX);
  cv::normalize(coarse, coarse, 0.0, 1.0, cv::NORM_MINMAX);
  cv::normalize(fine + coarse, texture, 0.0, 255.0, cv::NORM_MINMAX);
  return texture;
}

/// `texture` (float) moved by (dx, dy) px and quantised: out(x, y) = texture(x − dx, y − dy).
inline cv::Mat Shifted(const cv::Mat& texture, double dx, double dy) {
  const cv::Mat M = (cv::Mat_<double>(2, 3) << 1.0, 0.0, dx, 0.0, 1.0, dy);
  cv::Mat moved, out;
  cv::warpAffine(texture, moved, M, texture.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT_101);
  moved.convertTo(out, CV_8U);
  return out;
}

}  // namespace trackbed::testing_images
