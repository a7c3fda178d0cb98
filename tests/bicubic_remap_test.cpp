// The bicubic remap through a fixed map (perception/bicubic_remap.h) gives cv::remap's
// bytes: every one of the 1024 fractions with random pixels under it, taps half or
// wholly outside the source, and the rectification maps of a stereo pair with a
// calibration error.
#include "trackbed/perception/bicubic_remap.h"

#include <cstdint>
#include <numeric>

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/common/units.h"
#include "trackbed/perception/lens_undistorter.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::perception {
namespace {

cv::Mat Remapped(const cv::Mat& image, const cv::Mat& xy, const cv::Mat& a) {
  cv::Mat out;
  cv::remap(image, out, xy, a, cv::INTER_CUBIC, cv::BORDER_CONSTANT, 0);
  return out;
}

TEST(BicubicRemapTest, WeightsSumToOneInFixedPoint) {
  const std::vector<std::int16_t>& w = BicubicRemap::Weights();
  ASSERT_EQ(w.size(), 1024u * 16u);
  for (std::size_t e = 0; e < 1024; ++e) {
    EXPECT_EQ(std::accumulate(w.begin() + 16 * e, w.begin() + 16 * (e + 1), 0), 1 << 15) << e;
  }
  // No fraction: the pixel itself (32767 of 32768, OpenCV's rounding leaves one unit to
  // the tap diagonally below right).
  EXPECT_EQ(w[5], 32767);
  EXPECT_EQ(w[10], 1);
}

// Every fraction under every pixel of random images, some maps reaching outside.
TEST(BicubicRemapTest, GivesTheBytesOfCvRemapForEveryFraction) {
  const cv::Size source(97, 61), size(160, 128);  // 20480 pixels: each fraction 20 times a trial
  cv::RNG rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    cv::Mat xy(size, CV_16SC2), a(size, CV_16UC1);
    for (int y = 0; y < size.height; ++y) {
      for (int x = 0; x < size.width; ++x) {
        const int i = y * size.width + x;
        // Mostly inside; in a quarter of the trials anywhere from 5 px before to 5 px
        // past the source.
        const bool wide = trial % 4 == 0;
        xy.at<cv::Vec2s>(y, x) =
            cv::Vec2s(static_cast<short>(wide ? rng.uniform(-5, source.width + 5)
                                              : rng.uniform(1, source.width - 2)),
                      static_cast<short>(wide ? rng.uniform(-5, source.height + 5)
                                              : rng.uniform(1, source.height - 2)));
        // Each fraction in turn, with the map's upper bits set as they may be.
        a.at<std::uint16_t>(y, x) =
            static_cast<std::uint16_t>(((i + trial * 37) % 1024) | (trial % 3 == 0 ? 0xfc00 : 0));
      }
    }
    cv::Mat image(source, CV_8UC1);
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    if (trial % 5 == 1) image.setTo(255);  // saturation at the top
    const BicubicRemap remap(xy, a, source);
    cv::Mat ours;
    remap.Apply(image, &ours);
    const cv::Mat theirs = Remapped(image, xy, a);
    ASSERT_EQ(cv::countNonZero(ours != theirs), 0) << "trial " << trial;
  }
}

// A rectification's maps (a pair with a small calibration error, no lens), on a
// textured image and on a view into a larger one (rows not contiguous).
TEST(BicubicRemapTest, GivesTheBytesOfCvRemapOnARectificationMap) {
  geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(640, 480, units::Radians(80.0));
  const cv::Mat camera(CvCameraMatrix(K)), D = CvLensCoefficients(K.distortion);
  cv::Mat R;
  cv::Rodrigues(cv::Vec3d(0.004, -0.006, 0.003), R);
  const cv::Mat T = (cv::Mat_<double>(3, 1) << -0.12, 0.001, 0.0005);
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(camera, D, camera, D, CvImageSize(K), R, T, R1, R2, P1, P2, Q,
                    cv::CALIB_ZERO_DISPARITY, 0.0);
  for (const auto& [Rr, Pr] : {std::pair{R1, P1}, std::pair{R2, P2}}) {
    cv::Mat xy, a;
    UndistortRectifyMap(K, Rr, Pr, &xy, &a);
    cv::Mat big(CvImageSize(K) + cv::Size(13, 7), CV_8UC1);
    cv::randu(big, 0, 256);
    cv::GaussianBlur(big, big, {5, 5}, 1.2);
    const cv::Mat view = big(cv::Rect({5, 3}, CvImageSize(K)));
    const BicubicRemap remap(xy, a, CvImageSize(K));
    cv::Mat ours;
    remap.Apply(view, &ours);
    EXPECT_EQ(cv::countNonZero(ours != Remapped(view, xy, a)), 0);
    remap.Apply(view.clone(), &ours);
    EXPECT_EQ(cv::countNonZero(ours != Remapped(view, xy, a)), 0);
  }
}

TEST(BicubicRemapTest, RefusesWhatItCannotRemap) {
  const cv::Mat xy(4, 4, CV_16SC2, cv::Scalar(1, 1)), a(4, 4, CV_16UC1, cv::Scalar(0));
  EXPECT_THROW(BicubicRemap(xy, cv::Mat(4, 4, CV_32FC1), {8, 8}), std::invalid_argument);
  const BicubicRemap remap(xy, a, {8, 8});
  cv::Mat out;
  EXPECT_THROW(remap.Apply(cv::Mat(8, 9, CV_8UC1), &out), std::invalid_argument);
  EXPECT_THROW(remap.Apply(cv::Mat(8, 8, CV_16UC1), &out), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::perception
