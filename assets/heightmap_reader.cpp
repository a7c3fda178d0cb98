// Gazebo heightmap images through OpenCV (see heightmap_reader.h).
#include "trackbed/assets/heightmap_reader.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace trackbed::assets {

namespace {

[[noreturn]] void FailHeightmap(const sim::HeightmapOptions& o, const std::string& what) {
  throw AssetError(o.file + ": " + what);
}

// The image's pixels as read, refused unless one grey channel of 8 or 16 bits, square.
cv::Mat ReadGreyImage(const sim::HeightmapOptions& o) {
  if (!std::filesystem::is_regular_file(o.file)) FailHeightmap(o, "no such file");
  cv::Mat image;
  try {
    image = cv::imread(o.file, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    FailHeightmap(o, std::string("OpenCV cannot decode it: ") + e.what());
  }
  if (image.empty()) FailHeightmap(o, "not an image OpenCV can decode (PNG, ...)");
  if (image.channels() != 1) {
    FailHeightmap(o,
                  "has " + std::to_string(image.channels()) +
                      " channels: a heightmap is one grey channel (Gazebo's), e.g. `convert in.png "
                      "-colorspace Gray -depth 16 out.png`");
  }
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    FailHeightmap(o, "its pixels are not 8 or 16 bits unsigned, as Gazebo reads a heightmap image");
  }
  if (image.cols != image.rows) {
    FailHeightmap(o, "is " + std::to_string(image.cols) + " × " + std::to_string(image.rows) +
                         " pixels: a heightmap image is square, as Gazebo requires");
  }
  if (image.cols < 2) FailHeightmap(o, "has fewer than 2 × 2 pixels");
  // 64 million heights (512 MB), as for an elevation model's window (dem_reader.cpp).
  if (static_cast<double>(image.cols) * image.rows > 64e6) {
    FailHeightmap(o, "has more than 64 million pixels");
  }
  return image;
}

double HeightmapPixel(const cv::Mat& image, int c, int r) {
  return image.depth() == CV_8U ? image.at<std::uint8_t>(r, c) : image.at<std::uint16_t>(r, c);
}

}  // namespace

std::shared_ptr<const sim::ElevationGrid> ReadHeightmap(const sim::HeightmapOptions& options) {
  const cv::Mat image = ReadGreyImage(options);
  const int n = image.cols;
  double v_max = 0.0;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) v_max = std::max(v_max, HeightmapPixel(image, c, r));
  }
  const Eigen::Vector3d& size = options.size_m;
  const Eigen::Vector3d& pos = options.pos_m;
  std::vector<double> heights(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) {
    const int world_row = n - 1 - r;  // the image's top row lies at the highest y
    for (int c = 0; c < n; ++c) {
      const double v = v_max > 0.0 ? HeightmapPixel(image, c, r) / v_max : 0.0;
      heights[static_cast<std::size_t>(world_row) * n + c] = pos.z() + size.z() * v;
    }
  }
  const Eigen::Vector2d first(pos.x() - 0.5 * size.x(), pos.y() - 0.5 * size.y());
  const Eigen::Vector2d spacing(size.x() / (n - 1), size.y() / (n - 1));
  return std::make_shared<const sim::ElevationGrid>(n, n, first, spacing, std::move(heights));
}

}  // namespace trackbed::assets
