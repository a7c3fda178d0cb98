// Image statistics per band of rows (see image_statistics.h).
#include "trackbed/perception/image_statistics.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/common/option_error.h"
#include "trackbed/perception/feature_tracker.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::perception {
namespace {

constexpr int kMinBandRows = 8;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Which band row y falls in, or -1 (below the last band).
int BandOf(float y, const std::vector<cv::Range>& rows) {
  const int row = static_cast<int>(std::floor(y));
  for (std::size_t b = 0; b < rows.size(); ++b) {
    if (row >= rows[b].start && row < rows[b].end) return static_cast<int>(b);
  }
  return -1;
}

// The symmetric Hann window of n taps (numpy.hanning): 0.5 (1 − cos(2π i / (n − 1))).
std::vector<double> Hann(int n) {
  std::vector<double> w(n, 1.0);
  for (int i = 0; i < n && n > 1; ++i) w[i] = 0.5 * (1.0 - std::cos(2.0 * CV_PI * i / (n - 1)));
  return w;
}

// Multiplies the CV_64F image by the 2-D Hann window, the outer product of a Hann window
// along each axis. (cv::createHanningWindow is the square root of this product.)
void ApplyHannWindow(cv::Mat* f) {
  const std::vector<double> wy = Hann(f->rows), wx = Hann(f->cols);
  for (int y = 0; y < f->rows; ++y) {
    double* row = f->ptr<double>(y);
    for (int x = 0; x < f->cols; ++x) row[x] *= wy[y] * wx[x];
  }
}

// Least-squares slope of y against x.
double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= n;
  my /= n;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxx > 0.0 ? sxy / sxx : kNaN;
}

// The share of each band's FAST corners tracked into `next` (NaN without corners).
void TrackShares(const cv::Mat& gray, const cv::Mat& next, const std::vector<cv::KeyPoint>& fast,
                 const std::vector<cv::Range>& rows, const ImageStatisticsOptions& options,
                 std::vector<BandStatistics>* bands) {
  FeatureTrackerOptions lk;
  lk.window_px = options.lk_window_px;
  lk.pyramid_levels = options.lk_pyramid_levels;
  lk.max_iterations = 30;  // OpenCV's default criteria: 30 iterations or 0.01 px
  lk.epsilon_px = 0.01;
  lk.min_eigenvalue = 1e-4;  // OpenCV's default minEigThreshold
  lk.max_forward_backward_px = options.lk_max_forward_backward_px;
  lk.border_px = 0.0;
  FeatureTracker tracker(lk);
  std::vector<cv::Point2f> points, tracked_points;
  points.reserve(fast.size());
  for (const cv::KeyPoint& k : fast) points.push_back(k.pt);
  std::vector<TrackStatus> status;
  tracker.Track(gray, next, points, &tracked_points, &status);
  std::vector<int> corners(rows.size(), 0), tracked(rows.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int b = BandOf(points[i].y, rows);
    if (b < 0) continue;
    ++corners[b];
    if (status[i] == TrackStatus::kTracked) ++tracked[b];
  }
  for (std::size_t b = 0; b < rows.size(); ++b) {
    (*bands)[b].track_share = corners[b] > 0 ? static_cast<double>(tracked[b]) / corners[b] : kNaN;
  }
}

}  // namespace

void ImageStatisticsOptions::Validate() const {
  option_check::InRange("bands", bands, 1, 64);
  option_check::InRange("fast_threshold", fast_threshold, 1, 255);
  option_check::AtLeast("shi_tomasi_max_corners", shi_tomasi_max_corners, 1);
  if (!(std::isfinite(shi_tomasi_quality) && shi_tomasi_quality > 0.0 &&
        shi_tomasi_quality < 1.0)) {
    throw OptionError("shi_tomasi_quality",
                      "must be in (0, 1) (got " + option_check::Describe(shi_tomasi_quality) + ")");
  }
  option_check::NonNegative("shi_tomasi_min_distance_px", shi_tomasi_min_distance_px);
  option_check::AtLeast("spectrum_bins", spectrum_bins, 2);
  option_check::Positive("spectrum_min_frequency", spectrum_min_frequency);
  if (!(std::isfinite(spectrum_max_frequency) && spectrum_max_frequency > spectrum_min_frequency &&
        spectrum_max_frequency <= 0.5)) {
    throw OptionError("spectrum_max_frequency", "must be in (spectrum_min_frequency, 0.5] (got " +
                                                    option_check::Describe(spectrum_max_frequency) +
                                                    ")");
  }
  if (lk_window_px < 5 || lk_window_px % 2 == 0) {
    throw OptionError("lk_window_px",
                      "must be odd and >= 5 (got " + std::to_string(lk_window_px) + ")");
  }
  option_check::InRange("lk_pyramid_levels", lk_pyramid_levels, 0, 8);
  option_check::Positive("lk_max_forward_backward_px", lk_max_forward_backward_px);
}

std::vector<cv::Range> BandRows(int rows, int bands) {
  if (bands < 1 || rows / bands < kMinBandRows) {
    throw std::invalid_argument("BandRows: " + std::to_string(rows) + " rows cannot hold " +
                                std::to_string(bands) + " bands of at least " +
                                std::to_string(kMinBandRows) + " rows");
  }
  const int height = rows / bands;
  std::vector<cv::Range> ranges;
  for (int b = 0; b < bands; ++b) ranges.emplace_back(b * height, (b + 1) * height);
  return ranges;
}

double SpectrumSlope(const cv::Mat& gray, const ImageStatisticsOptions& options) {
  CheckGray8(gray, "SpectrumSlope");
  options.Validate();
  if (gray.rows < kMinBandRows || gray.cols < kMinBandRows) {
    throw std::invalid_argument("SpectrumSlope: needs at least 8 x 8 pixels");
  }
  cv::Mat f;
  gray.convertTo(f, CV_64F);
  f -= cv::mean(f)[0];
  ApplyHannWindow(&f);
  cv::Mat spectrum;
  cv::dft(f, spectrum, cv::DFT_COMPLEX_OUTPUT);

  const int H = f.rows, W = f.cols, n = options.spectrum_bins;
  const double lo = std::log(options.spectrum_min_frequency);
  const double hi = std::log(options.spectrum_max_frequency);
  std::vector<double> power(n, 0.0);
  std::vector<int> count(n, 0);
  for (int y = 0; y < H; ++y) {
    const double fy = static_cast<double>(y <= H / 2 ? y : y - H) / H;
    const cv::Vec2d* row = spectrum.ptr<cv::Vec2d>(y);
    for (int x = 0; x < W; ++x) {
      const double fx = static_cast<double>(x <= W / 2 ? x : x - W) / W;
      const double r = std::hypot(fx, fy);
      if (!(r >= options.spectrum_min_frequency && r <= options.spectrum_max_frequency)) continue;
      const int b = std::min(n - 1, static_cast<int>((std::log(r) - lo) / (hi - lo) * n));
      power[b] += row[x][0] * row[x][0] + row[x][1] * row[x][1];
      ++count[b];
    }
  }
  std::vector<double> xs, ys;
  for (int b = 0; b < n; ++b) {
    if (count[b] == 0 || !(power[b] > 0.0)) continue;
    xs.push_back(lo + (b + 0.5) * (hi - lo) / n);  // the bin's centre in ln f
    ys.push_back(std::log(power[b] / count[b]));
  }
  return xs.size() >= 2 ? Slope(xs, ys) : kNaN;
}

std::vector<BandStatistics> MeasureImage(const cv::Mat& gray, const cv::Mat& next,
                                         const ImageStatisticsOptions& options) {
  CheckGray8(gray, "MeasureImage");
  options.Validate();
  if (!next.empty() && (next.size() != gray.size() || next.type() != CV_8UC1)) {
    throw std::invalid_argument("MeasureImage: the next image must be CV_8UC1 of the same size");
  }
  const std::vector<cv::Range> rows = BandRows(gray.rows, options.bands);
  std::vector<BandStatistics> bands(rows.size());

  std::vector<cv::KeyPoint> fast;
  cv::FastFeatureDetector::create(options.fast_threshold, options.fast_nonmax_suppression)
      ->detect(gray, fast);
  std::vector<cv::Point2f> shi_tomasi;
  cv::goodFeaturesToTrack(gray, shi_tomasi, options.shi_tomasi_max_corners,
                          options.shi_tomasi_quality, options.shi_tomasi_min_distance_px);
  for (const cv::KeyPoint& k : fast) {
    const int b = BandOf(k.pt.y, rows);
    if (b >= 0) bands[b].fast_corners += 1.0;
  }
  for (const cv::Point2f& p : shi_tomasi) {
    const int b = BandOf(p.y, rows);
    if (b >= 0) bands[b].shi_tomasi_corners += 1.0;
  }

  cv::Mat f, gx, gy, magnitude;
  gray.convertTo(f, CV_32F);
  cv::Sobel(f, gx, CV_32F, 1, 0, 3);
  cv::Sobel(f, gy, CV_32F, 0, 1, 3);
  cv::magnitude(gx, gy, magnitude);
  for (std::size_t b = 0; b < rows.size(); ++b) {
    BandStatistics& s = bands[b];
    s.row_begin = rows[b].start;
    s.row_end = rows[b].end;
    s.mean_gradient = cv::mean(magnitude.rowRange(rows[b]))[0];
    s.spectrum_slope = SpectrumSlope(gray.rowRange(rows[b]), options);
    cv::Scalar mean, stddev;
    cv::meanStdDev(gray.rowRange(rows[b]), mean, stddev);
    s.grey_mean = mean[0];
    s.grey_std = stddev[0];
    s.track_share = kNaN;
  }
  if (!next.empty()) TrackShares(gray, next, fast, rows, options, &bands);
  return bands;
}

void SequenceStatistics::Add(const std::vector<BandStatistics>& image) {
  if (images_ == 0) {
    sums_.assign(image.size(), BandStatistics{});
    track_share_images_.assign(image.size(), 0);
    for (std::size_t b = 0; b < image.size(); ++b) {
      sums_[b].row_begin = image[b].row_begin;
      sums_[b].row_end = image[b].row_end;
    }
  }
  if (image.size() != sums_.size()) {
    throw std::invalid_argument("SequenceStatistics::Add: an image with " +
                                std::to_string(image.size()) + " bands after images with " +
                                std::to_string(sums_.size()));
  }
  for (std::size_t b = 0; b < image.size(); ++b) {
    const BandStatistics& s = image[b];
    BandStatistics& sum = sums_[b];
    if (s.row_begin != sum.row_begin || s.row_end != sum.row_end) {
      throw std::invalid_argument("SequenceStatistics::Add: band " + std::to_string(b + 1) +
                                  "'s rows differ from the first image's (images of one size)");
    }
    sum.fast_corners += s.fast_corners;
    sum.shi_tomasi_corners += s.shi_tomasi_corners;
    sum.mean_gradient += s.mean_gradient;
    sum.spectrum_slope += s.spectrum_slope;
    sum.grey_mean += s.grey_mean;
    sum.grey_std += s.grey_std;
    if (std::isfinite(s.track_share)) {
      sum.track_share += s.track_share;
      ++track_share_images_[b];
    }
  }
  ++images_;
}

std::vector<BandStatistics> SequenceStatistics::Mean() const {
  std::vector<BandStatistics> mean = sums_;
  const double n = static_cast<double>(images_);
  for (std::size_t b = 0; b < mean.size(); ++b) {
    BandStatistics& m = mean[b];
    m.fast_corners /= n;
    m.shi_tomasi_corners /= n;
    m.mean_gradient /= n;
    m.spectrum_slope /= n;
    m.grey_mean /= n;
    m.grey_std /= n;
    m.track_share = track_share_images_[b] > 0 ? m.track_share / track_share_images_[b] : kNaN;
  }
  return mean;
}

}  // namespace trackbed::perception
