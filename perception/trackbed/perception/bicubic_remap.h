// cv::remap's bicubic interpolation of 8-bit grey images through a fixed map, with its
// bytes: the same 4 × 4 fixed-point weights per 1/32 px (OpenCV's table, rebuilt
// here as initInterTab2D builds it), the same integer sums and rounding, black outside
// the source (BORDER_CONSTANT 0). A map used for every frame (a rectification) is
// decoded once into each output pixel's first source pixel and weights, so a frame
// costs only the sums: four 4-byte rows and two multiply-adds per pixel with SSE2,
// where cv::remap decodes the map per block and sums pixel by pixel
// (docs/results/2026-12-07-cheaper-closed-loop.md).
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace trackbed::perception {

class BicubicRemap {
 public:
  /// `map_xy` (CV_16SC2: integer source column and row) and `map_a` (CV_16UC1: the
  /// 1/32 px fractions, row · 32 + column, in its low ten bits) as cv::convertMaps
  /// makes them, for sources of `source_size`. Throws std::invalid_argument for maps
  /// of another type or of different sizes.
  BicubicRemap(const cv::Mat& map_xy, const cv::Mat& map_a, cv::Size source_size);

  /// *out = cv::remap(source, map_xy, map_a, INTER_CUBIC, BORDER_CONSTANT, 0), byte for
  /// byte. `source`: CV_8UC1 of source_size (throws std::invalid_argument otherwise);
  /// *out must not share its pixels (it is written as the source is read).
  void Apply(const cv::Mat& source, cv::Mat* out) const;

  /// OpenCV's fixed-point bicubic weights: 1024 entries (fraction row · 32 + column) of
  /// 4 × 4 taps, row-major, summing to 2^15.
  static const std::vector<std::int16_t>& Weights();

 private:
  // An output pixel some of whose taps fall outside the source.
  struct Border {
    std::int32_t pixel;        // row-major index in the output
    std::int32_t column, row;  // of its first (top-left) tap in the source
    std::uint16_t entry;       // in Weights()
  };

  cv::Size source_size_, size_;
  // Per output pixel: the source offset (row · width + column) of its first tap, its
  // entry in Weights(), and whether all 16 taps lie in the source (else it is in
  // border_ and its offset unused).
  std::vector<std::int32_t> offset_;
  std::vector<std::uint16_t> entry_;
  std::vector<std::uint8_t> inside_;
  std::vector<Border> border_;
};

}  // namespace trackbed::perception
