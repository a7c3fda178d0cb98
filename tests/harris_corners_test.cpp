// Harris corners with an absolute threshold: synthetic images with known corners,
// the contrast law of R, thresholds, bucketing, and option validation.
#include "trackbed/perception/harris_corners.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <utility>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "real_data.h"
#include "trackbed/common/option_error.h"
#include "trackbed/perception/kitti_sequence.h"

namespace trackbed::perception {
namespace {

constexpr int kSquarePx = 40;

/// Checkerboard of cols x rows squares of kSquarePx filling the image (black/white).
cv::Mat Checkerboard(int cols, int rows) {
  cv::Mat image(rows * kSquarePx, cols * kSquarePx, CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<unsigned char>(y, x) = ((x / kSquarePx + y / kSquarePx) % 2) ? 255 : 0;
    }
  }
  return image;
}

/// Uniform noise in [0, 255] from a fixed seed.
cv::Mat Noise(int width, int height, std::uint64_t seed) {
  cv::Mat image(height, width, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

std::pair<int, int> Cell(const Corner& c, const cv::Mat& image, int cols, int rows) {
  const int cx = std::clamp(static_cast<int>(std::floor(c.position.x * static_cast<float>(cols) /
                                                        static_cast<float>(image.cols))),
                            0, cols - 1);
  const int cy = std::clamp(static_cast<int>(std::floor(c.position.y * static_cast<float>(rows) /
                                                        static_cast<float>(image.rows))),
                            0, rows - 1);
  return {cx, cy};
}

TEST(HarrisCornersTest, FlatImageHasNoCorners) {
  const cv::Mat flat(240, 320, CV_8UC1, cv::Scalar(128));
  EXPECT_TRUE(DetectHarrisCorners(flat, HarrisOptions{}).empty());
  HarrisOptions zero_threshold;
  zero_threshold.min_response = 0.0;  // R == 0 everywhere: still nothing above it
  EXPECT_TRUE(DetectHarrisCorners(flat, zero_threshold).empty());
}

TEST(HarrisCornersTest, CheckerboardGivesExactlyTheInnerCorners) {
  const int cols = 8, rows = 6;
  const cv::Mat board = Checkerboard(cols, rows);
  const std::vector<Corner> corners = DetectHarrisCorners(board, HarrisOptions{});
  ASSERT_EQ(corners.size(), static_cast<std::size_t>((cols - 1) * (rows - 1)));
  // Each inner corner lies between pixels 40i-1 and 40i: at 40i - 0.5.
  std::vector<int> hits((cols - 1) * (rows - 1), 0);
  for (const Corner& c : corners) {
    const int i = static_cast<int>(std::lround((c.position.x + 0.5f) / kSquarePx));
    const int j = static_cast<int>(std::lround((c.position.y + 0.5f) / kSquarePx));
    ASSERT_GE(i, 1);
    ASSERT_LE(i, cols - 1);
    ASSERT_GE(j, 1);
    ASSERT_LE(j, rows - 1);
    EXPECT_NEAR(c.position.x, kSquarePx * i - 0.5f, 1.5f);
    EXPECT_NEAR(c.position.y, kSquarePx * j - 0.5f, 1.5f);
    ++hits[static_cast<std::size_t>((j - 1) * (cols - 1) + (i - 1))];
  }
  for (int h : hits) EXPECT_EQ(h, 1);
}

TEST(HarrisCornersTest, CheckerboardCornerIsFoundForEveryKernelSize) {
  const cv::Mat board = Checkerboard(8, 6);
  for (int aperture : {3, 5, 7}) {
    for (int block : {3, 5, 7, 9}) {
      HarrisOptions options;
      options.aperture_size = aperture;
      options.block_size = block;
      const std::vector<Corner> corners = DetectHarrisCorners(board, options);
      EXPECT_EQ(corners.size(), 35u) << "aperture " << aperture << " block " << block;
      for (const Corner& c : corners) {
        const float x = kSquarePx * std::round((c.position.x + 0.5f) / kSquarePx) - 0.5f;
        const float y = kSquarePx * std::round((c.position.y + 0.5f) / kSquarePx) - 0.5f;
        EXPECT_NEAR(c.position.x, x, 1.5f) << "aperture " << aperture << " block " << block;
        EXPECT_NEAR(c.position.y, y, 1.5f) << "aperture " << aperture << " block " << block;
      }
    }
  }
}

TEST(HarrisCornersTest, SobelNormalisationGivesTheSlopeOnARamp) {
  // On a ramp I = s·x (s per pixel, image in [0, 1]) every aperture gives Ix = s, so
  // the normalised tensor is M = [s² 0; 0 0] and R = -k s⁴, whatever the kernel sizes.
  cv::Mat ramp(64, 256, CV_8UC1);
  for (int y = 0; y < ramp.rows; ++y) {
    for (int x = 0; x < ramp.cols; ++x)
      ramp.at<unsigned char>(y, x) = static_cast<unsigned char>(x);
  }
  const double s = 1.0 / 255.0;
  for (int aperture : {3, 5, 7}) {
    for (int block : {3, 7}) {
      HarrisOptions options;
      options.aperture_size = aperture;
      options.block_size = block;
      const cv::Mat R = HarrisResponse(ramp, options);
      EXPECT_NEAR(R.at<float>(32, 128), -options.k * std::pow(s, 4), 1e-6 * std::pow(s, 4))
          << "aperture " << aperture << " block " << block;
    }
  }
}

TEST(HarrisCornersTest, NoiseHasManyCornersAndCountFallsWithThreshold) {
  const cv::Mat noise = Noise(320, 240, 12345);
  HarrisOptions options;
  std::size_t previous = 0;
  bool first = true;
  // Uniform noise: local maxima of R lie between ~1e-4 and ~3e-3 (default kernels).
  for (double threshold : {1e-4, 3e-4, 6e-4, 1e-3, 2e-3}) {
    options.min_response = threshold;
    const std::size_t count = DetectHarrisCorners(noise, options).size();
    if (first) {
      EXPECT_GT(count, 500u);  // the default threshold: most local maxima of noise
      first = false;
    } else {
      EXPECT_LT(count, previous) << "min_response " << threshold;
    }
    previous = count;
  }
}

TEST(HarrisCornersTest, CornersAreStrongestFirstAboveThresholdAndInsideBorder) {
  const cv::Mat noise = Noise(320, 240, 7);
  HarrisOptions options;
  options.border_px = 12;
  const std::vector<Corner> corners = DetectHarrisCorners(noise, options);
  ASSERT_FALSE(corners.empty());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Corner& c = corners[i];
    EXPECT_GT(c.response, options.min_response);
    if (i > 0) {
      EXPECT_LE(c.response, corners[i - 1].response);
    }
    EXPECT_GE(c.position.x, options.border_px - 0.5f);
    EXPECT_GE(c.position.y, options.border_px - 0.5f);
    EXPECT_LE(c.position.x, noise.cols - 1 - options.border_px + 0.5f);
    EXPECT_LE(c.position.y, noise.rows - 1 - options.border_px + 0.5f);
  }
  // Non-maximum suppression: integer peaks are more than the radius apart in x or y,
  // and sub-pixel refinement moves each by at most half a pixel.
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      const cv::Point2f d = corners[i].position - corners[j].position;
      EXPECT_GE(std::max(std::abs(d.x), std::abs(d.y)), static_cast<float>(options.nms_radius_px));
    }
  }
}

TEST(HarrisCornersTest, MaxCornersKeepsTheStrongest) {
  const cv::Mat noise = Noise(320, 240, 99);
  HarrisOptions options;
  const std::vector<Corner> all = DetectHarrisCorners(noise, options);
  options.max_corners = 50;
  const std::vector<Corner> best = DetectHarrisCorners(noise, options);
  ASSERT_GT(all.size(), 50u);
  ASSERT_EQ(best.size(), 50u);
  for (std::size_t i = 0; i < best.size(); ++i) {
    EXPECT_EQ(best[i].position, all[i].position);
    EXPECT_EQ(best[i].response, all[i].response);
  }
}

TEST(HarrisCornersTest, HalvingContrastDividesResponseBy16) {
  // Even grey levels, so halving is exact in 8 bits: R scales as contrast⁴.
  cv::Mat full = Noise(320, 240, 2024);
  full &= cv::Scalar(0xFE);
  cv::Mat half;
  full.convertTo(half, CV_8UC1, 0.5);
  ASSERT_EQ(cv::norm(half * 2, full, cv::NORM_INF), 0.0);

  HarrisOptions options;
  const cv::Mat R_full = HarrisResponse(full, options);
  const cv::Mat R_half = HarrisResponse(half, options);
  double max_full = 0.0;
  cv::minMaxLoc(cv::abs(R_full), nullptr, &max_full);
  ASSERT_GT(max_full, 0.0);
  EXPECT_LE(cv::norm(R_half * 16.0, R_full, cv::NORM_INF), 1e-6 * max_full);

  options.min_response = 0.0;
  const std::vector<Corner> a = DetectHarrisCorners(full, options);
  const std::vector<Corner> b = DetectHarrisCorners(half, options);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position);
    EXPECT_NEAR(b[i].response * 16.0, a[i].response, 1e-6 * a[i].response);
  }
}

TEST(HarrisCornersTest, BucketedKeepsAtMostPerCellAndCoversEveryCell) {
  const cv::Mat noise = Noise(320, 240, 4242);
  const int cols = 4, rows = 3, per_cell = 5;
  HarrisOptions options;
  const std::vector<Corner> bucketed =
      DetectHarrisCornersBucketed(noise, options, cols, rows, per_cell);
  const std::vector<Corner> all = DetectHarrisCorners(noise, options);

  std::map<std::pair<int, int>, std::vector<Corner>> by_cell, all_by_cell;
  for (const Corner& c : bucketed) by_cell[Cell(c, noise, cols, rows)].push_back(c);
  for (const Corner& c : all) all_by_cell[Cell(c, noise, cols, rows)].push_back(c);
  ASSERT_EQ(by_cell.size(), static_cast<std::size_t>(cols * rows)) << "every cell covered";
  for (const auto& [cell, corners] : by_cell) {
    EXPECT_LE(corners.size(), static_cast<std::size_t>(per_cell));
    // ... and they are that cell's strongest corners of the unbucketed detector.
    const std::vector<Corner>& reference = all_by_cell[cell];
    ASSERT_EQ(corners.size(), std::min<std::size_t>(per_cell, reference.size()));
    for (std::size_t i = 0; i < corners.size(); ++i) {
      EXPECT_EQ(corners[i].position, reference[i].position);
    }
  }
  for (std::size_t i = 1; i < bucketed.size(); ++i) {
    EXPECT_LE(bucketed[i].response, bucketed[i - 1].response);
  }

  options.max_corners = 7;
  EXPECT_EQ(DetectHarrisCornersBucketed(noise, options, cols, rows, per_cell).size(), 7u);
}

TEST(HarrisCornersRealDataTest, KittiImageHasCornersSpreadOverTheImage) {
  const std::filesystem::path dir = trackbed::testing_data::RealData("kitti06");
  TRACKBED_NEEDS_REAL_DATA(dir);
  const KittiSequence sequence(dir);
  const cv::Mat image = sequence.LoadLeft(0);
  HarrisOptions options;
  EXPECT_GT(DetectHarrisCorners(image, options).size(), 100u);
  // The lower two thirds (road, cars, vegetation) are textured in every column band.
  const int cols = 8, rows = 3;
  const std::vector<Corner> bucketed = DetectHarrisCornersBucketed(image, options, cols, rows, 10);
  std::map<std::pair<int, int>, int> count;
  for (const Corner& c : bucketed) ++count[Cell(c, image, cols, rows)];
  for (int cx = 0; cx < cols; ++cx) {
    EXPECT_GT(count[std::make_pair(cx, 1)], 0) << "cell column " << cx;
  }
}

TEST(HarrisCornersTest, RejectsBadImagesAndArguments) {
  const HarrisOptions options;
  EXPECT_THROW(DetectHarrisCorners(cv::Mat(), options), std::invalid_argument);
  EXPECT_THROW(DetectHarrisCorners(cv::Mat(20, 20, CV_8UC3, cv::Scalar::all(0)), options),
               std::invalid_argument);
  EXPECT_THROW(DetectHarrisCorners(cv::Mat(20, 20, CV_32F, cv::Scalar(0)), options),
               std::invalid_argument);
  const cv::Mat image(40, 40, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(DetectHarrisCornersBucketed(image, options, 0, 2, 3), std::invalid_argument);
  EXPECT_THROW(DetectHarrisCornersBucketed(image, options, 2, 0, 3), std::invalid_argument);
  EXPECT_THROW(DetectHarrisCornersBucketed(image, options, 2, 2, 0), std::invalid_argument);
}

TEST(HarrisCornersTest, ValidateNamesTheField) {
  EXPECT_NO_THROW(HarrisOptions{}.Validate());
  const auto expect_field = [](HarrisOptions options, const std::string& field) {
    try {
      options.Validate();
      ADD_FAILURE() << "no error for " << field;
    } catch (const OptionError& e) {
      EXPECT_EQ(e.field(), field);
    }
    // Detection validates too.
    EXPECT_THROW(DetectHarrisCorners(cv::Mat(40, 40, CV_8UC1, cv::Scalar(0)), options),
                 OptionError);
  };
  HarrisOptions o;
  o.block_size = 4;
  expect_field(o, "block_size");
  o = {};
  o.block_size = 1;
  expect_field(o, "block_size");
  o = {};
  o.aperture_size = 1;
  expect_field(o, "aperture_size");
  o = {};
  o.k = 0.25;
  expect_field(o, "k");
  o = {};
  o.k = 0.0;
  expect_field(o, "k");
  o = {};
  o.min_response = -1e-6;
  expect_field(o, "min_response");
  o = {};
  o.nms_radius_px = 0;
  expect_field(o, "nms_radius_px");
  o = {};
  o.border_px = -1;
  expect_field(o, "border_px");
  o = {};
  o.max_corners = -3;
  expect_field(o, "max_corners");
}

}  // namespace
}  // namespace trackbed::perception
