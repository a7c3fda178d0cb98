// Image statistics per band: constructed images with known answers (corners of squares
// counted per band, a ramp's and a constant image's gradient, the spectrum slope of
// 1/f^α noise, the track share of a shifted and of an unrelated image), the means over
// a sequence and a folder, option checks, and the KITTI 06 reference row
// (docs/image_statistics.md).
#include "trackbed/perception/image_statistics.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "real_data.h"
#include "textured_images.h"
#include "trackbed/common/option_error.h"
#include "trackbed/perception/image_sequence_statistics.h"

namespace trackbed::perception {
namespace {

namespace fs = std::filesystem;

// Bright 12 × 12 px squares (grey 200) on a dark ground (grey 40), one at each given
// top-left corner.
cv::Mat Squares(int width, int height, const std::vector<cv::Point>& corners) {
  cv::Mat image(height, width, CV_8UC1, cv::Scalar(40));
  for (const cv::Point& p : corners) image(cv::Rect(p.x, p.y, 12, 12)).setTo(200);
  return image;
}

// Seeded noise whose power is f^−α exactly: amplitudes f^(−α/2) with random phases (the
// zero frequency left out), inverse DFT (of the Hermitian half), scaled to a standard
// deviation of 40 grey levels around 128.
cv::Mat PowerLawNoise(int width, int height, double alpha, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat spectrum(height, width, CV_64FC2, cv::Scalar::all(0));
  for (int y = 0; y < height; ++y) {
    const double fy = static_cast<double>(y <= height / 2 ? y : y - height) / height;
    for (int x = 0; x < width; ++x) {
      const double fx = static_cast<double>(x <= width / 2 ? x : x - width) / width;
      const double f = std::hypot(fx, fy);
      if (f == 0.0) continue;
      const double amplitude = std::pow(f, -alpha / 2.0);
      const double phase = rng.uniform(0.0, 2.0 * CV_PI);
      spectrum.at<cv::Vec2d>(y, x) = {amplitude * std::cos(phase), amplitude * std::sin(phase)};
    }
  }
  cv::Mat field;
  cv::dft(spectrum, field, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT);
  cv::Scalar mean, stddev;
  cv::meanStdDev(field, mean, stddev);
  cv::Mat image;
  field.convertTo(image, CV_8U, 40.0 / stddev[0], 128.0 - 40.0 * mean[0] / stddev[0]);
  return image;
}

using testing_images::Shifted;
using testing_images::Texture;

TEST(ImageStatisticsTest, BandsAreEqualRowsFromTheTop) {
  const std::vector<cv::Range> kitti = BandRows(370, 4);  // the last 2 rows in no band
  ASSERT_EQ(kitti.size(), 4u);
  EXPECT_EQ(kitti[0], cv::Range(0, 92));
  EXPECT_EQ(kitti[1], cv::Range(92, 184));
  EXPECT_EQ(kitti[2], cv::Range(184, 276));
  EXPECT_EQ(kitti[3], cv::Range(276, 368));
  EXPECT_EQ(BandRows(480, 4)[3], cv::Range(360, 480));
  EXPECT_EQ(BandRows(16, 2)[1], cv::Range(8, 16));
  EXPECT_THROW(BandRows(15, 2), std::invalid_argument);  // bands of 7 rows
  EXPECT_THROW(BandRows(100, 0), std::invalid_argument);
}

TEST(ImageStatisticsTest, CornersOfSquaresAreCountedInTheirBand) {
  // Two squares in band 1 (rows 0–39) and five in band 3 (rows 80–119), blurred (σ = 1
  // px) so that each corner is one peak: FAST and Shi–Tomasi find each square's 4
  // corners, and nothing in the flat bands.
  cv::Mat image =
      Squares(300, 160, {{20, 10}, {80, 14}, {20, 90}, {60, 92}, {100, 88}, {140, 90}, {200, 94}});
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0);
  const std::vector<BandStatistics> bands = MeasureImage(image, cv::Mat());
  ASSERT_EQ(bands.size(), 4u);
  const double expected[4] = {8, 0, 20, 0};
  for (int b = 0; b < 4; ++b) {
    EXPECT_EQ(bands[b].fast_corners, expected[b]) << "band " << b + 1;
    EXPECT_EQ(bands[b].shi_tomasi_corners, expected[b]) << "band " << b + 1;
  }
  EXPECT_EQ(bands[1].row_begin, 40);
  EXPECT_EQ(bands[1].row_end, 80);
  // Band 2 is untouched ground: grey 40 exactly, no gradient, no spectrum, no track.
  EXPECT_EQ(bands[1].grey_mean, 40.0);
  EXPECT_EQ(bands[1].grey_std, 0.0);
  EXPECT_EQ(bands[1].mean_gradient, 0.0);
  EXPECT_TRUE(std::isnan(bands[1].spectrum_slope));
  EXPECT_TRUE(std::isnan(bands[1].track_share));  // no next image
  EXPECT_GT(bands[0].mean_gradient, 0.0);
}

TEST(ImageStatisticsTest, ConstantImageHasNothingAndARampItsSlope) {
  const cv::Mat constant(120, 200, CV_8UC1, cv::Scalar(90));
  for (const BandStatistics& b : MeasureImage(constant, constant)) {
    EXPECT_EQ(b.fast_corners, 0.0);
    EXPECT_EQ(b.shi_tomasi_corners, 0.0);
    EXPECT_EQ(b.mean_gradient, 0.0);
    EXPECT_EQ(b.grey_mean, 90.0);
    EXPECT_EQ(b.grey_std, 0.0);
    EXPECT_TRUE(std::isnan(b.spectrum_slope));
    EXPECT_TRUE(std::isnan(b.track_share));  // no corners to track
  }
  // I(x, y) = x over 256 columns: the unnormalised Sobel reads 8 inside and 0 in the
  // two border columns (reflected), so the mean is 8 · 254 / 256 in every band.
  cv::Mat ramp(64, 256, CV_8UC1);
  for (int y = 0; y < ramp.rows; ++y) {
    for (int x = 0; x < ramp.cols; ++x) ramp.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(x);
  }
  for (const BandStatistics& b : MeasureImage(ramp, cv::Mat())) {
    EXPECT_NEAR(b.mean_gradient, 8.0 * 254.0 / 256.0, 1e-5);
    EXPECT_NEAR(b.grey_mean, 127.5, 1e-9);
    EXPECT_NEAR(b.grey_std, std::sqrt((256.0 * 256.0 - 1.0) / 12.0), 1e-9);
  }
}

TEST(ImageStatisticsTest, PowerLawNoiseGivesItsExponent) {
  // Power exactly ∝ f^−α (random phases only): the slope reads −α within 0.05, on a
  // square image and on a band of KITTI's shape (wide and low).
  for (double alpha : {1.0, 2.0, 3.0}) {
    EXPECT_NEAR(SpectrumSlope(PowerLawNoise(512, 512, alpha, 3)), -alpha, 0.05) << alpha;
    EXPECT_NEAR(SpectrumSlope(PowerLawNoise(1024, 96, alpha, 4)), -alpha, 0.05) << alpha;
  }
  // Through MeasureImage, each band of a 1/f² image: a band cut out of the field is not
  // periodic and its spectrum is one sample, not exactly f^−2 (here −2.03, −2.01, −2.04,
  // −1.89), hence 0.15.
  for (const BandStatistics& b : MeasureImage(PowerLawNoise(1024, 384, 2.0, 5), cv::Mat())) {
    EXPECT_NEAR(b.spectrum_slope, -2.0, 0.15) << "rows " << b.row_begin;
  }
}

TEST(ImageStatisticsTest, ShiftedImageIsTrackedAndAnUnrelatedOneIsNot) {
  const cv::Mat texture = Texture(400, 240, 7);
  const cv::Mat image = Shifted(texture, 0.0, 0.0);
  for (const BandStatistics& b : MeasureImage(image, Shifted(texture, 2.3, 1.1))) {
    EXPECT_GT(b.fast_corners, 300.0);
    EXPECT_GE(b.track_share, 0.99) << "rows " << b.row_begin;
  }
  for (const BandStatistics& b : MeasureImage(image, Shifted(Texture(400, 240, 8), 0.0, 0.0))) {
    EXPECT_LT(b.track_share, 0.1) << "rows " << b.row_begin;
  }
  EXPECT_THROW(MeasureImage(image, cv::Mat(100, 100, CV_8UC1, cv::Scalar(0))),
               std::invalid_argument);
}

TEST(ImageStatisticsTest, SequenceMeansAreImageByImage) {
  std::vector<BandStatistics> a(2), b(2);
  a[0] = {0, 10, 4.0, 2.0, 1.0, -2.0, 100.0, 10.0, 0.5};
  a[1] = {10, 20, 0.0, 0.0, 0.0, std::nan(""), 50.0, 0.0, std::nan("")};
  b[0] = {0, 10, 8.0, 6.0, 3.0, -3.0, 120.0, 20.0, 1.0};
  b[1] = {10, 20, 2.0, 1.0, 1.0, -1.0, 70.0, 4.0, 0.25};
  SequenceStatistics sequence;
  EXPECT_TRUE(sequence.Mean().empty());
  sequence.Add(a);
  sequence.Add(b);
  EXPECT_EQ(sequence.images(), 2u);
  const std::vector<BandStatistics> m = sequence.Mean();
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].row_end, 10);
  EXPECT_EQ(m[0].fast_corners, 6.0);
  EXPECT_EQ(m[0].shi_tomasi_corners, 4.0);
  EXPECT_EQ(m[0].mean_gradient, 2.0);
  EXPECT_EQ(m[0].spectrum_slope, -2.5);
  EXPECT_EQ(m[0].grey_mean, 110.0);
  EXPECT_EQ(m[0].grey_std, 15.0);
  EXPECT_EQ(m[0].track_share, 0.75);
  EXPECT_EQ(m[1].track_share, 0.25);  // over the one image where it is defined
  EXPECT_EQ(m[1].grey_mean, 60.0);
  EXPECT_THROW(sequence.Add(std::vector<BandStatistics>(3)), std::invalid_argument);
  std::vector<BandStatistics> other_rows = a;
  other_rows[1].row_end = 21;
  EXPECT_THROW(sequence.Add(other_rows), std::invalid_argument);
}

TEST(ImageStatisticsTest, FolderSelectionAndLayouts) {
  const fs::path root = fs::path(::testing::TempDir()) / "image_statistics_folder";
  fs::remove_all(root);
  // A run folder's layout: images/image_0/000000.png … 000006.png, the texture moving
  // 1 px right per frame.
  const fs::path left = root / "run" / "images" / "image_0";
  fs::create_directories(left);
  const cv::Mat texture = Texture(200, 96, 11);
  for (int k = 0; k < 7; ++k) {
    char name[16];
    std::snprintf(name, sizeof(name), "%06d.png", k);
    ASSERT_TRUE(cv::imwrite((left / name).string(), Shifted(texture, k, 0.0)));
  }
  EXPECT_EQ(FindImages(root / "run").size(), 7u);
  EXPECT_EQ(FindImages(root / "run" / "images").size(), 7u);  // the KITTI layout
  EXPECT_EQ(FindImages(left).size(), 7u);                     // the images themselves

  ImageSelection selection;
  selection.every = 3;  // images 0, 3, 6; 6 is the last: no next image
  const FolderStatistics all = MeasureFolder(root / "run", selection);
  ASSERT_EQ(all.images.size(), 3u);
  EXPECT_EQ(all.images[2].filename(), "000006.png");
  EXPECT_EQ(all.image_size, cv::Size(200, 96));
  for (const BandStatistics& b : all.bands) EXPECT_GE(b.track_share, 0.97);
  selection.first = 1;
  selection.count = 2;  // images 1 and 4
  const FolderStatistics two = MeasureFolder(root / "run", selection);
  ASSERT_EQ(two.images.size(), 2u);
  EXPECT_EQ(two.images[1].filename(), "000004.png");
  selection.first = 7;
  EXPECT_THROW(MeasureFolder(root / "run", selection), std::runtime_error);

  fs::create_directories(root / "empty");
  EXPECT_THROW(FindImages(root / "empty"), std::runtime_error);
  EXPECT_THROW(FindImages(root / "missing"), std::runtime_error);
  // An image of another size stops the measurement, naming it.
  ASSERT_TRUE(cv::imwrite((left / "000003.png").string(), cv::Mat(50, 50, CV_8UC1, 7)));
  selection = ImageSelection{};
  selection.every = 1;
  try {
    MeasureFolder(root / "run", selection);
    ADD_FAILURE() << "no error for an image of another size";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("000003.png"), std::string::npos) << e.what();
  }
  fs::remove_all(root);
}

TEST(ImageStatisticsTest, ValidateNamesTheField) {
  EXPECT_NO_THROW(ImageStatisticsOptions{}.Validate());
  EXPECT_NO_THROW(ImageSelection{}.Validate());
  const auto expect_field = [](auto options, const std::string& field) {
    try {
      options.Validate();
      ADD_FAILURE() << "no error for " << field;
    } catch (const OptionError& e) {
      EXPECT_EQ(e.field(), field);
    }
  };
  ImageStatisticsOptions o;
  o.bands = 0;
  expect_field(o, "bands");
  o = {};
  o.fast_threshold = 0;
  expect_field(o, "fast_threshold");
  o = {};
  o.shi_tomasi_max_corners = 0;
  expect_field(o, "shi_tomasi_max_corners");
  o = {};
  o.shi_tomasi_quality = 1.0;
  expect_field(o, "shi_tomasi_quality");
  o = {};
  o.shi_tomasi_min_distance_px = -1.0;
  expect_field(o, "shi_tomasi_min_distance_px");
  o = {};
  o.spectrum_bins = 1;
  expect_field(o, "spectrum_bins");
  o = {};
  o.spectrum_min_frequency = 0.0;
  expect_field(o, "spectrum_min_frequency");
  o = {};
  o.spectrum_max_frequency = 0.01;
  expect_field(o, "spectrum_max_frequency");
  o = {};
  o.lk_window_px = 20;
  expect_field(o, "lk_window_px");
  o = {};
  o.lk_pyramid_levels = 9;
  expect_field(o, "lk_pyramid_levels");
  o = {};
  o.lk_max_forward_backward_px = 0.0;
  expect_field(o, "lk_max_forward_backward_px");
  ImageSelection s;
  s.every = 0;
  expect_field(s, "every");
  s = {};
  s.first = -1;
  expect_field(s, "first");
  s = {};
  s.count = -1;
  expect_field(s, "count");
}

// KITTI 06, frames 0–50, every fifth (11 images): the reference row of
// docs/image_statistics.md, each figure to 1 %.
TEST(ImageStatisticsRealDataTest, Kitti06ReproducesTheReferenceRow) {
  const fs::path dir = trackbed::testing_data::RealData("kitti06");
  TRACKBED_NEEDS_REAL_DATA(dir / "image_0");
  ImageSelection selection;
  selection.count = 11;
  const FolderStatistics s = MeasureFolder(dir, selection);
  ASSERT_EQ(s.images.size(), 11u);
  EXPECT_EQ(s.images.back().filename(), "000050.png");
  ASSERT_EQ(s.bands.size(), 4u);
  const double fast[4] = {1137, 1956, 1070, 408};
  const double shi_tomasi[4] = {534, 863, 459, 135};
  const double gradient[4] = {62, 93, 69, 44};
  const double slope[4] = {-2.22, -2.20, -2.23, -2.50};
  for (int b = 0; b < 4; ++b) {
    const BandStatistics& m = s.bands[b];
    EXPECT_NEAR(m.fast_corners, fast[b], 0.01 * fast[b]) << "band " << b + 1;
    EXPECT_NEAR(m.shi_tomasi_corners, shi_tomasi[b], 0.01 * shi_tomasi[b]) << "band " << b + 1;
    EXPECT_NEAR(m.mean_gradient, gradient[b], 0.01 * gradient[b]) << "band " << b + 1;
    EXPECT_NEAR(m.spectrum_slope, slope[b], 0.01 * std::fabs(slope[b])) << "band " << b + 1;
    // No reference: the road near the car moves tens of pixels a frame (0.23 tracked),
    // the rest 0.68–0.81.
    EXPECT_GT(m.track_share, 0.15) << "band " << b + 1;
    EXPECT_LT(m.track_share, 0.9) << "band " << b + 1;
    std::printf(
        "band %d: FAST %.1f, Shi-Tomasi %.1f, gradient %.2f, slope %.3f, grey %.1f +- "
        "%.1f, tracked %.3f\n",
        b + 1, m.fast_corners, m.shi_tomasi_corners, m.mean_gradient, m.spectrum_slope, m.grey_mean,
        m.grey_std, m.track_share);
  }
}

}  // namespace
}  // namespace trackbed::perception
