// Sparse ZNCC stereo matching: known disparities of synthetic rectified pairs
// (fronto-parallel and slanted textured planes, with a gain change between cameras),
// and the rejections: flat patches, repetitive texture, image borders, range limits.
#include "trackbed/perception/stereo_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "trackbed/common/option_error.h"

namespace trackbed::perception {
namespace {

constexpr double kPi = 3.14159265358979323846;

cv::Mat Texture(int width, int height, std::uint64_t seed) {
  cv::Mat noise(height, width, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, noise, 0.0, 255.0, cv::NORM_MINMAX);
  return noise;
}

/// A rectified pair of a textured surface with disparity field d(x_left, y): the left
/// image is the texture, the right image at x_r shows the texture at the x_l with
/// x_l − d(x_l, y) = x_r (solved by fixed-point iteration), times `gain` plus `offset`.
struct Pair {
  cv::Mat left, right;
};
Pair MakePair(const cv::Mat& texture, const std::function<double(double, double)>& d,
              double gain = 1.0, double offset = 0.0) {
  cv::Mat map_x(texture.size(), CV_32F), map_y(texture.size(), CV_32F);
  for (int y = 0; y < texture.rows; ++y) {
    for (int x = 0; x < texture.cols; ++x) {
      double xl = x + d(x, y);
      for (int k = 0; k < 20; ++k) xl = x + d(xl, y);
      map_x.at<float>(y, x) = static_cast<float>(xl);
      map_y.at<float>(y, x) = static_cast<float>(y);
    }
  }
  cv::Mat right_f;
  cv::remap(texture, right_f, map_x, map_y, cv::INTER_CUBIC, cv::BORDER_REFLECT_101);
  Pair pair;
  texture.convertTo(pair.left, CV_8U);
  right_f.convertTo(pair.right, CV_8U, gain, offset);
  return pair;
}

/// Matches a grid of sub-pixel points; returns the worst and RMS |error| and counts.
struct Score {
  double worst_px = 0.0;
  double rms_px = 0.0;
  int within_0_2_px = 0;
  int valid = 0;
  int total = 0;
};
Score MatchGrid(StereoMatcher& matcher, const Pair& pair,
                const std::function<double(double, double)>& d) {
  Score s;
  for (float y = 20.3f; y < static_cast<float>(pair.left.rows) - 20.0f; y += 9.0f) {
    for (float x = 60.7f; x < static_cast<float>(pair.left.cols) - 20.0f; x += 11.0f) {
      ++s.total;
      const StereoMatch m = matcher.Match(pair.left, pair.right, cv::Point2f(x, y));
      if (!m.valid()) continue;
      ++s.valid;
      const double error = std::abs(m.disparity_px - d(x, y));
      s.worst_px = std::max(s.worst_px, error);
      s.rms_px += error * error;
      s.within_0_2_px += error <= 0.2 ? 1 : 0;
    }
  }
  s.rms_px = s.valid > 0 ? std::sqrt(s.rms_px / s.valid) : 0.0;
  return s;
}

TEST(StereoMatcherTest, FrontoParallelPlaneDisparityWithinAFifthOfAPixel) {
  const auto d = [](double, double) { return 17.35; };
  const Pair pair = MakePair(Texture(360, 200, 21), d);
  StereoMatcher matcher;
  const Score s = MatchGrid(matcher, pair, d);
  EXPECT_GT(s.valid, s.total * 95 / 100) << s.valid << " of " << s.total;
  EXPECT_LT(s.worst_px, 0.2);
  std::printf("fronto-parallel plane: %d/%d matched, worst error %.3f px\n", s.valid, s.total,
              s.worst_px);
}

TEST(StereoMatcherTest, SlantedPlaneWithGainChangeWithinAFifthOfAPixel) {
  // A plane seen at an angle: disparity grows to the right and downwards (like a road),
  // and the right camera has 20 % less gain and an offset.
  const auto d = [](double x, double y) { return 8.0 + 0.02 * x + 0.05 * y; };
  const Pair pair = MakePair(Texture(360, 200, 22), d, 0.8, 20.0);
  StereoMatcher matcher;
  const Score s = MatchGrid(matcher, pair, d);
  EXPECT_GT(s.valid, s.total * 9 / 10) << s.valid << " of " << s.total;
  EXPECT_LT(s.worst_px, 0.2);
  std::printf("slanted plane, gain 0.8: %d/%d matched, worst error %.3f px\n", s.valid, s.total,
              s.worst_px);
}

TEST(StereoMatcherTest, FloorSeenFromALowCameraNeedsTheDisparityGradient) {
  // A floor seen from height h: d grows by baseline/h per row (0.3 px/px for a 0.12 m
  // baseline at 0.4 m), ±1.5 px across an 11-px window. The refinement models it; the
  // parabola alone (a constant-disparity window) averages the rows unevenly.
  const auto d = [](double, double y) { return 2.0 + 0.3 * y; };
  const Pair pair = MakePair(Texture(360, 200, 25), d);
  StereoMatcher refined;
  StereoMatcherOptions no_refinement;
  no_refinement.refinement_iterations = 0;
  StereoMatcher parabola(no_refinement);
  const Score with = MatchGrid(refined, pair, d);
  const Score without = MatchGrid(parabola, pair, d);
  EXPECT_GT(with.valid, with.total * 9 / 10) << with.valid << " of " << with.total;
  EXPECT_GE(with.within_0_2_px, with.valid * 99 / 100);
  EXPECT_LT(with.rms_px, 0.1);
  EXPECT_LT(with.rms_px, without.rms_px / 3.0);
  std::printf(
      "floor, 0.3 px/row: %d/%d matched, RMS error %.3f px, %d within 0.2 px (parabola only: "
      "RMS %.3f px, %d within 0.2 px)\n",
      with.valid, with.total, with.rms_px, with.within_0_2_px, without.rms_px,
      without.within_0_2_px);
}

TEST(StereoMatcherTest, BatchMatchesAgreeWithSinglePoints) {
  const auto d = [](double, double) { return 11.6; };
  const Pair pair = MakePair(Texture(200, 120, 23), d);
  StereoMatcher matcher;
  const std::vector<cv::Point2f> points = {{50.5f, 40.2f}, {120.0f, 60.0f}, {3.0f, 60.0f}};
  std::vector<StereoMatch> matches;
  const int valid = matcher.Match(pair.left, pair.right, points, &matches);
  ASSERT_EQ(matches.size(), points.size());
  EXPECT_EQ(valid, 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const StereoMatch one = matcher.Match(pair.left, pair.right, points[i]);
    EXPECT_EQ(one.status, matches[i].status);
    EXPECT_EQ(one.disparity_px, matches[i].disparity_px);
  }
  EXPECT_EQ(matches[2].status, StereoMatchStatus::kOutOfImage);  // window crosses the border
}

TEST(StereoMatcherTest, FlatPatchIsLowTexture) {
  const cv::Mat flat(100, 200, CV_8UC1, cv::Scalar(120));
  StereoMatcher matcher;
  EXPECT_EQ(matcher.Match(flat, flat, cv::Point2f(100.0f, 50.0f)).status,
            StereoMatchStatus::kLowTexture);
}

TEST(StereoMatcherTest, RepetitiveTextureIsAmbiguous) {
  // Vertical stripes with a period of 9 px: every 9 px of disparity matches equally well.
  cv::Mat stripes(100, 300, CV_32F);
  for (int y = 0; y < stripes.rows; ++y) {
    for (int x = 0; x < stripes.cols; ++x) {
      stripes.at<float>(y, x) = static_cast<float>(128.0 + 100.0 * std::sin(2.0 * kPi * x / 9.0));
    }
  }
  const Pair pair = MakePair(stripes, [](double, double) { return 20.0; });
  StereoMatcher matcher;
  const StereoMatch m = matcher.Match(pair.left, pair.right, cv::Point2f(200.0f, 50.0f));
  EXPECT_FALSE(m.valid());
  EXPECT_EQ(m.status, StereoMatchStatus::kAmbiguous);
}

TEST(StereoMatcherTest, DisparityBeyondTheRangeIsNotMatched) {
  const auto d = [](double, double) { return 40.0; };
  const Pair pair = MakePair(Texture(300, 100, 24), d);
  StereoMatcherOptions options;
  options.max_disparity_px = 30;  // the true disparity is outside [0, 30]
  StereoMatcher matcher(options);
  int matched = 0;
  for (float x = 120.0f; x < 280.0f; x += 10.0f) {
    matched += matcher.Match(pair.left, pair.right, cv::Point2f(x, 50.0f)).valid() ? 1 : 0;
  }
  EXPECT_EQ(matched, 0);
}

TEST(StereoMatcherTest, MismatchedImagesThrow) {
  const cv::Mat a(100, 200, CV_8UC1, cv::Scalar(0)), b(100, 201, CV_8UC1, cv::Scalar(0));
  StereoMatcher matcher;
  std::vector<StereoMatch> matches;
  EXPECT_THROW(matcher.Match(a, b, {{10.0f, 10.0f}}, &matches), std::invalid_argument);
  EXPECT_THROW(matcher.Match(a, cv::Mat(), cv::Point2f(10.0f, 10.0f)), std::invalid_argument);
}

TEST(StereoMatcherTest, InvalidOptionsNameTheField) {
  const auto field_of = [](const StereoMatcherOptions& o) {
    try {
      o.Validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return std::string("(valid)");
  };
  StereoMatcherOptions o;
  EXPECT_EQ(field_of(o), "(valid)");
  o.window_px = 4;
  EXPECT_EQ(field_of(o), "window_px");
  o = {};
  o.min_disparity_px = -1;
  EXPECT_EQ(field_of(o), "min_disparity_px");
  o = {};
  o.max_disparity_px = 1;
  EXPECT_EQ(field_of(o), "max_disparity_px");
  o = {};
  o.min_zncc = 1.5;
  EXPECT_EQ(field_of(o), "min_zncc");
  o = {};
  o.uniqueness_ratio = -0.1;
  EXPECT_EQ(field_of(o), "uniqueness_ratio");
  o = {};
  o.max_left_right_px = -1.0;
  EXPECT_EQ(field_of(o), "max_left_right_px");
  o = {};
  o.min_texture = -2.0;
  EXPECT_EQ(field_of(o), "min_texture");
  o = {};
  o.window_px = 2;
  EXPECT_THROW(StereoMatcher{o}, OptionError);
}

}  // namespace
}  // namespace trackbed::perception
