// Pyramidal Lucas–Kanade tracking with bounds and forward–backward checks (see
// feature_tracker.h).
#include "trackbed/perception/feature_tracker.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/video/tracking.hpp>

#include "trackbed/common/option_error.h"

namespace trackbed::perception {
namespace {

bool Inside(const cv::Point2f& p, cv::Size size, float border) {
  return std::isfinite(p.x) && std::isfinite(p.y) && p.x >= border && p.y >= border &&
         p.x <= static_cast<float>(size.width - 1) - border &&
         p.y <= static_cast<float>(size.height - 1) - border;
}

}  // namespace

void FeatureTrackerOptions::Validate() const {
  if (window_px < 5 || window_px % 2 == 0) {
    throw OptionError("window_px", "must be odd and >= 5 (got " + std::to_string(window_px) + ")");
  }
  if (pyramid_levels < 0 || pyramid_levels > 8) {
    throw OptionError("pyramid_levels",
                      "must be in [0, 8] (got " + std::to_string(pyramid_levels) + ")");
  }
  if (max_iterations < 1) {
    throw OptionError("max_iterations",
                      "must be >= 1 (got " + std::to_string(max_iterations) + ")");
  }
  option_check::Positive("epsilon_px", epsilon_px);
  option_check::NonNegative("min_eigenvalue", min_eigenvalue);
  option_check::NonNegative("max_forward_backward_px", max_forward_backward_px);
  option_check::NonNegative("border_px", border_px);
}

const char* ToString(TrackStatus status) {
  switch (status) {
    case TrackStatus::kTracked:
      return "tracked";
    case TrackStatus::kLost:
      return "lost";
    case TrackStatus::kOutOfImage:
      return "out_of_image";
    case TrackStatus::kForwardBackward:
      return "forward_backward";
  }
  return "unknown";
}

FeatureTracker::FeatureTracker(const FeatureTrackerOptions& options) : options_(options) {
  options_.Validate();
}

void FeatureTracker::BuildPyramid(const cv::Mat& gray, TrackingPyramid* pyramid) const {
  if (gray.empty() || gray.type() != CV_8UC1) {
    throw std::invalid_argument("FeatureTracker::BuildPyramid: needs a non-empty CV_8UC1 image");
  }
  // Derivatives are stored with the levels so that calcOpticalFlowPyrLK does not
  // recompute them for every call (forward, backward, next frame). Data are copied
  // (tryReuseInputImage = false): the pyramid never aliases the caller's image.
  cv::buildOpticalFlowPyramid(gray, pyramid->levels, {options_.window_px, options_.window_px},
                              options_.pyramid_levels, /*withDerivatives=*/true,
                              cv::BORDER_REFLECT_101, cv::BORDER_CONSTANT,
                              /*tryReuseInputImage=*/false);
  pyramid->image_size = gray.size();
}

int FeatureTracker::Track(const TrackingPyramid& prev, const TrackingPyramid& curr,
                          const std::vector<cv::Point2f>& prev_points,
                          std::vector<cv::Point2f>* curr_points, std::vector<TrackStatus>* status,
                          bool use_initial_guess) {
  if (prev.empty() || curr.empty() || prev.image_size != curr.image_size) {
    throw std::invalid_argument(
        "FeatureTracker::Track: pyramids must be built and of the same image size");
  }
  const std::size_t n = prev_points.size();
  if (use_initial_guess && curr_points->size() != n) {
    throw std::invalid_argument("FeatureTracker::Track: initial guess has " +
                                std::to_string(curr_points->size()) + " points for " +
                                std::to_string(n) + " points");
  }
  status->assign(n, TrackStatus::kLost);
  if (!use_initial_guess) curr_points->assign(prev_points.begin(), prev_points.end());
  if (n == 0) return 0;

  const cv::Size window(options_.window_px, options_.window_px);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS,
                                  options_.max_iterations, options_.epsilon_px);
  if (use_initial_guess) {
    guess_shift_.resize(n);
    for (std::size_t i = 0; i < n; ++i) guess_shift_[i] = (*curr_points)[i] - prev_points[i];
  }
  const int flags = use_initial_guess ? cv::OPTFLOW_USE_INITIAL_FLOW : 0;
  cv::calcOpticalFlowPyrLK(prev.levels, curr.levels, prev_points, *curr_points, lk_status_,
                           cv::noArray(), window, options_.pyramid_levels, criteria, flags,
                           options_.min_eigenvalue);

  const float border = static_cast<float>(options_.border_px);
  int tracked = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!lk_status_[i]) continue;
    if (!Inside((*curr_points)[i], curr.image_size, border)) {
      (*status)[i] = TrackStatus::kOutOfImage;
      continue;
    }
    (*status)[i] = TrackStatus::kTracked;
    ++tracked;
  }
  if (options_.max_forward_backward_px <= 0.0 || tracked == 0) return tracked;

  // Backward track of the survivors (Kalal et al. 2010), each starting where its forward
  // track ended, moved back by the guess's displacement if there was one (with none, it
  // starts exactly there, the standard check). Starting at the original point instead
  // would let a track that did not move in either direction pass.
  fb_index_.clear();
  fb_from_.clear();
  back_points_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if ((*status)[i] != TrackStatus::kTracked) continue;
    fb_index_.push_back(i);
    fb_from_.push_back((*curr_points)[i]);
    back_points_.push_back(use_initial_guess ? (*curr_points)[i] - guess_shift_[i]
                                             : (*curr_points)[i]);
  }
  cv::calcOpticalFlowPyrLK(curr.levels, prev.levels, fb_from_, back_points_, back_status_,
                           cv::noArray(), window, options_.pyramid_levels, criteria,
                           cv::OPTFLOW_USE_INITIAL_FLOW, options_.min_eigenvalue);
  const float max_fb_sq =
      static_cast<float>(options_.max_forward_backward_px * options_.max_forward_backward_px);
  for (std::size_t k = 0; k < fb_index_.size(); ++k) {
    const std::size_t i = fb_index_[k];
    const cv::Point2f d = back_points_[k] - prev_points[i];
    if (!back_status_[k] || !(d.x * d.x + d.y * d.y <= max_fb_sq)) {
      (*status)[i] = TrackStatus::kForwardBackward;
      --tracked;
    }
  }
  return tracked;
}

int FeatureTracker::Track(const cv::Mat& prev_gray, const cv::Mat& curr_gray,
                          const std::vector<cv::Point2f>& prev_points,
                          std::vector<cv::Point2f>* curr_points, std::vector<TrackStatus>* status) {
  if (prev_gray.size() != curr_gray.size()) {
    throw std::invalid_argument("FeatureTracker::Track: images differ in size");
  }
  BuildPyramid(prev_gray, &scratch_prev_);
  BuildPyramid(curr_gray, &scratch_curr_);
  return Track(scratch_prev_, scratch_curr_, prev_points, curr_points, status, false);
}

}  // namespace trackbed::perception
