// Harris corners with an absolute threshold (see harris_corners.h).
#include "trackbed/perception/harris_corners.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "trackbed/common/option_error.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::perception {
namespace {

/// Offset in [-0.5, 0.5] of the vertex of the parabola through (-1, a), (0, b), (1, c).
float ParabolaPeak(float a, float b, float c) {
  const float curvature = a - 2.0f * b + c;
  if (!(curvature < 0.0f)) return 0.0f;
  return std::clamp(0.5f * (a - c) / curvature, -0.5f, 0.5f);
}

/// All corners after thresholding and non-maximum suppression, strongest first.
std::vector<Corner> Candidates(const cv::Mat& gray, const HarrisOptions& options) {
  const cv::Mat R = HarrisResponse(gray, options);
  const int r = options.nms_radius_px;
  cv::Mat local_max;
  cv::dilate(R, local_max, cv::getStructuringElement(cv::MORPH_RECT, {2 * r + 1, 2 * r + 1}));

  struct Peak {
    int x, y;
    float response;
  };
  std::vector<Peak> peaks;
  const int b = options.border_px;
  const float threshold = static_cast<float>(options.min_response);
  for (int y = b; y < R.rows - b; ++y) {
    const float* row = R.ptr<float>(y);
    const float* max_row = local_max.ptr<float>(y);
    for (int x = b; x < R.cols - b; ++x) {
      if (row[x] > threshold && row[x] >= max_row[x]) peaks.push_back({x, y, row[x]});
    }
  }
  // Strongest first; equal responses in raster order, so the result is deterministic.
  std::stable_sort(peaks.begin(), peaks.end(),
                   [](const Peak& p, const Peak& q) { return p.response > q.response; });

  // Plateaus (equal responses within one window, e.g. a corner exactly between four
  // pixels) leave several local maxima: keep the first, suppress the rest.
  cv::Mat taken(R.size(), CV_8UC1, cv::Scalar(0));
  std::vector<Corner> corners;
  corners.reserve(peaks.size());
  for (const Peak& p : peaks) {
    if (taken.at<unsigned char>(p.y, p.x)) continue;
    const int x0 = std::max(0, p.x - r), x1 = std::min(R.cols - 1, p.x + r);
    const int y0 = std::max(0, p.y - r), y1 = std::min(R.rows - 1, p.y + r);
    taken(cv::Range(y0, y1 + 1), cv::Range(x0, x1 + 1)).setTo(1);

    float dx = 0.0f, dy = 0.0f;
    if (p.x > 0 && p.x < R.cols - 1) {
      dx = ParabolaPeak(R.at<float>(p.y, p.x - 1), p.response, R.at<float>(p.y, p.x + 1));
    }
    if (p.y > 0 && p.y < R.rows - 1) {
      dy = ParabolaPeak(R.at<float>(p.y - 1, p.x), p.response, R.at<float>(p.y + 1, p.x));
    }
    corners.push_back(
        {cv::Point2f(static_cast<float>(p.x) + dx, static_cast<float>(p.y) + dy), p.response});
  }
  return corners;
}

}  // namespace

void HarrisOptions::Validate() const {
  if (block_size < 3 || block_size % 2 == 0) {
    throw OptionError("block_size",
                      "must be odd and >= 3 (got " + std::to_string(block_size) + ")");
  }
  if (aperture_size != 3 && aperture_size != 5 && aperture_size != 7) {
    throw OptionError("aperture_size",
                      "must be 3, 5 or 7 (got " + std::to_string(aperture_size) + ")");
  }
  if (!(std::isfinite(k) && k > 0.0 && k < 0.25)) {
    throw OptionError("k", "must be in (0, 0.25) (got " + option_check::Describe(k) + ")");
  }
  option_check::NonNegative("min_response", min_response);
  if (nms_radius_px < 1) {
    throw OptionError("nms_radius_px", "must be >= 1 (got " + std::to_string(nms_radius_px) + ")");
  }
  if (border_px < 0) {
    throw OptionError("border_px", "must be >= 0 (got " + std::to_string(border_px) + ")");
  }
  if (max_corners < 0) {
    throw OptionError("max_corners", "must be >= 0 (got " + std::to_string(max_corners) + ")");
  }
}

cv::Mat HarrisResponse(const cv::Mat& gray, const HarrisOptions& options) {
  CheckGray8(gray, "HarrisResponse");
  options.Validate();
  cv::Mat image;
  gray.convertTo(image, CV_32F, 1.0 / 255.0);

  // Sobel of aperture a = (smoothing, sum 2^(a-1)) ⊗ (derivative, first moment
  // 2^(a-2)): dividing by 2^(2a-3) makes Ix the slope per pixel for every aperture.
  const double sobel_scale = 1.0 / static_cast<double>(1 << (2 * options.aperture_size - 3));
  cv::Mat Ix, Iy;
  cv::Sobel(image, Ix, CV_32F, 1, 0, options.aperture_size, sobel_scale, 0.0,
            cv::BORDER_REFLECT_101);
  cv::Sobel(image, Iy, CV_32F, 0, 1, options.aperture_size, sobel_scale, 0.0,
            cv::BORDER_REFLECT_101);
  const cv::Mat Ixx = Ix.mul(Ix), Iyy = Iy.mul(Iy), Ixy = Ix.mul(Iy);

  // Weighted mean over the window: a separable Gaussian of block_size taps whose
  // weights sum to 1 (getGaussianKernel with sigma <= 0 picks OpenCV's default
  // 0.3((n-1)/2 - 1) + 0.8 and normalises). Unlike a box, it makes an ideal corner a
  // single peak instead of a (block - aperture + 1)-wide plateau.
  const cv::Mat window = cv::getGaussianKernel(options.block_size, -1.0, CV_32F);
  cv::Mat Mxx, Myy, Mxy;
  cv::sepFilter2D(Ixx, Mxx, CV_32F, window, window, {-1, -1}, 0.0, cv::BORDER_REFLECT_101);
  cv::sepFilter2D(Iyy, Myy, CV_32F, window, window, {-1, -1}, 0.0, cv::BORDER_REFLECT_101);
  cv::sepFilter2D(Ixy, Mxy, CV_32F, window, window, {-1, -1}, 0.0, cv::BORDER_REFLECT_101);

  // R = det M − k (trace M)²   (Harris & Stephens 1988)
  const float k = static_cast<float>(options.k);
  cv::Mat R(gray.size(), CV_32F);
  for (int y = 0; y < R.rows; ++y) {
    const float* a = Mxx.ptr<float>(y);
    const float* c = Myy.ptr<float>(y);
    const float* b = Mxy.ptr<float>(y);
    float* out = R.ptr<float>(y);
    for (int x = 0; x < R.cols; ++x) {
      const float trace = a[x] + c[x];
      out[x] = a[x] * c[x] - b[x] * b[x] - k * trace * trace;
    }
  }
  return R;
}

std::vector<Corner> DetectHarrisCorners(const cv::Mat& gray, const HarrisOptions& options) {
  CheckGray8(gray, "DetectHarrisCorners");
  std::vector<Corner> corners = Candidates(gray, options);
  if (options.max_corners > 0 && corners.size() > static_cast<std::size_t>(options.max_corners)) {
    corners.resize(static_cast<std::size_t>(options.max_corners));
  }
  return corners;
}

std::vector<Corner> DetectHarrisCornersBucketed(const cv::Mat& gray, const HarrisOptions& options,
                                                int cols, int rows, int per_cell) {
  CheckGray8(gray, "DetectHarrisCornersBucketed");
  if (cols < 1 || rows < 1 || per_cell < 1) {
    throw std::invalid_argument(
        "DetectHarrisCornersBucketed: cols, rows and per_cell must be >= 1");
  }
  const std::vector<Corner> candidates = Candidates(gray, options);
  std::vector<int> count(static_cast<std::size_t>(cols * rows), 0);
  std::vector<Corner> corners;
  for (const Corner& c : candidates) {  // strongest first, so each cell keeps its best
    const int cx = std::clamp(static_cast<int>(std::floor(c.position.x * static_cast<float>(cols) /
                                                          static_cast<float>(gray.cols))),
                              0, cols - 1);
    const int cy = std::clamp(static_cast<int>(std::floor(c.position.y * static_cast<float>(rows) /
                                                          static_cast<float>(gray.rows))),
                              0, rows - 1);
    int& n = count[static_cast<std::size_t>(cy * cols + cx)];
    if (n >= per_cell) continue;
    ++n;
    corners.push_back(c);
    if (options.max_corners > 0 &&
        corners.size() >= static_cast<std::size_t>(options.max_corners)) {
      break;
    }
  }
  return corners;
}

}  // namespace trackbed::perception
