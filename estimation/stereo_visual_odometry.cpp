// Frame-to-frame stereo visual odometry (see stereo_visual_odometry.h).
#include "trackbed/estimation/stereo_visual_odometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "trackbed/common/option_error.h"
#include "trackbed/common/se3.h"
#include "trackbed/common/units.h"
#include "trackbed/estimation/constant_velocity.h"

namespace trackbed::estimation {

// ---------------------------------------------------------------------------------------
// StereoVisualOdometry.

void StereoVisualOdometryOptions::Validate() const {
  option_check::Nested("harris", harris);
  if (grid_cols < 1) {
    throw OptionError("grid_cols", "must be >= 1 (got " + std::to_string(grid_cols) + ")");
  }
  if (grid_rows < 1) {
    throw OptionError("grid_rows", "must be >= 1 (got " + std::to_string(grid_rows) + ")");
  }
  if (exhausted_cell_retry_frames < 1) {
    throw OptionError("exhausted_cell_retry_frames",
                      "must be >= 1 (got " + std::to_string(exhausted_cell_retry_frames) + ")");
  }
  if (features_per_cell < 1) {
    throw OptionError("features_per_cell",
                      "must be >= 1 (got " + std::to_string(features_per_cell) + ")");
  }
  option_check::NonNegative("min_feature_distance_px", min_feature_distance_px);
  option_check::Nested("tracker", tracker);
  option_check::Nested("matcher", matcher);
  option_check::Positive("max_depth_m", max_depth_m);
  option_check::Nested("ransac", ransac);
  if (min_inliers < 3) {
    throw OptionError("min_inliers", "must be >= 3 (got " + std::to_string(min_inliers) + ")");
  }
  option_check::Nested("refinement", refinement);
  option_check::Positive("max_translation_per_frame_m", max_translation_per_frame_m);
  option_check::InRange("max_rotation_per_frame_deg", max_rotation_per_frame_deg, 1e-3, 180.0);
  option_check::Positive("max_acceleration_mps2", max_acceleration_mps2);
  option_check::Positive("max_angular_acceleration_dps2", max_angular_acceleration_dps2);
  option_check::Positive("max_rotation_prior_error_deg", max_rotation_prior_error_deg);
  option_check::NonNegative("rotation_prior_bias_std_radps", rotation_prior_bias_std_radps);
  option_check::NonNegative("rotation_prior_noise_density", rotation_prior_noise_density);
  if (!(rotation_prior_bias_std_radps > 0.0 || rotation_prior_noise_density > 0.0)) {
    throw OptionError("rotation_prior_noise_density",
                      "must be > 0 where rotation_prior_bias_std_radps is 0");
  }
  option_check::Positive("disparity_offset_prior_std_px", disparity_offset_prior_std_px);
  option_check::Positive("disparity_offset_walk_px", disparity_offset_walk_px);
  option_check::NonNegative("calibration_disparity_offset_std_px",
                            calibration_disparity_offset_std_px);
}

const char* ToString(VoStatus status) {
  switch (status) {
    case VoStatus::kOk:
      return "ok";
    case VoStatus::kFirstFrame:
      return "first_frame";
    case VoStatus::kTooFewFeatures:
      return "too_few_features";
    case VoStatus::kTooFewInliers:
      return "too_few_inliers";
    case VoStatus::kRansacFailed:
      return "ransac_failed";
    case VoStatus::kImplausibleMotion:
      return "implausible_motion";
    case VoStatus::kInconsistentMotion:
      return "inconsistent_motion";
    case VoStatus::kNotProcessed:
      return "not_processed";
  }
  return "unknown";
}

namespace {
StereoVisualOdometryOptions Validated(const StereoVisualOdometryOptions& options) {
  options.Validate();
  return options;
}

StereoMotionOptions MotionOptionsOf(const StereoVisualOdometryOptions& options) {
  StereoMotionOptions m;
  m.ransac = options.ransac;
  m.refinement = options.refinement;
  m.min_inliers = options.min_inliers;
  return m;
}

}  // namespace

namespace {

geometry::StereoCamera Checked(const geometry::StereoCamera& camera) {
  camera.Validate();
  return camera;
}

}  // namespace

StereoVisualOdometry::StereoVisualOdometry(const geometry::StereoCamera& camera,
                                           const StereoVisualOdometryOptions& options)
    : camera_(Checked(camera)),
      options_(Validated(options)),
      motion_options_(MotionOptionsOf(options_)),
      tracker_(options_.tracker),
      matcher_(options_.matcher),
      rng_(options_.seed),
      disparity_offset_var_px2_(PriorOffsetVariance()) {}

void StereoVisualOdometry::Reset() {
  has_previous_ = false;
  prev_.clear();
  curr_.clear();
  T_world_cam_ = Eigen::Isometry3d::Identity();
  last_T_curr_prev_ = Eigen::Isometry3d::Identity();
  last_motion_valid_ = false;
  rng_ = random::Generator(options_.seed);
  disparity_offset_px_ = 0.0;
  disparity_offset_var_px2_ = PriorOffsetVariance();
}

bool StereoVisualOdometry::UsablePoint(const Eigen::Vector3d& p) const {
  return p.allFinite() && p.z() > 0.0 && p.z() <= options_.max_depth_m;
}

void StereoVisualOdometry::Replenish(const cv::Mat& left, const cv::Mat& right,
                                     Features* features) {
  const int cols = options_.grid_cols, rows = options_.grid_rows;
  const auto cell_of = [&](const cv::Point2f& p) {
    // The cell formula of DetectHarrisCornersBucketed.
    const int cx = std::clamp(static_cast<int>(std::floor(p.x * static_cast<float>(cols) /
                                                          static_cast<float>(left.cols))),
                              0, cols - 1);
    const int cy = std::clamp(static_cast<int>(std::floor(p.y * static_cast<float>(rows) /
                                                          static_cast<float>(left.rows))),
                              0, rows - 1);
    return static_cast<std::size_t>(cy * cols + cx);
  };
  cell_count_.assign(static_cast<std::size_t>(cols * rows), 0);
  if (cell_retry_frame_.size() != cell_count_.size())
    cell_retry_frame_.assign(cell_count_.size(), 0);
  for (const cv::Point2f& p : features->points) ++cell_count_[cell_of(p)];
  const int per_cell = options_.features_per_cell;
  bool any = false;
  for (std::size_t c = 0; c < cell_count_.size(); ++c) {
    any = any || (cell_count_[c] < per_cell && frame_index_ >= cell_retry_frame_[c]);
  }
  if (!any) return;

  // Occupancy: a square of side 2r − 1 around each feature (Chebyshev distance < r).
  const int r = static_cast<int>(std::ceil(options_.min_feature_distance_px));
  occupancy_.create(left.size(), CV_8UC1);
  occupancy_.setTo(0);
  const auto occupy = [&](const cv::Point2f& p) {
    if (r <= 0) return;
    const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
    const int x0 = std::max(0, x - r + 1), x1 = std::min(left.cols - 1, x + r - 1);
    const int y0 = std::max(0, y - r + 1), y1 = std::min(left.rows - 1, y + r - 1);
    if (x0 > x1 || y0 > y1) return;
    occupancy_(cv::Range(y0, y1 + 1), cv::Range(x0, x1 + 1)).setTo(1);
  };
  for (const cv::Point2f& p : features->points) occupy(p);

  // Harris only where needed: in each under-filled cell, on the cell grown by a margin
  // so that the response, the non-maximum suppression and the border test inside the
  // cell are those of the whole image (the filters reach block/2 + aperture/2 px, the
  // suppression nms_radius_px more; the ROI's own border is then outside the cell).
  const perception::HarrisOptions& harris = options_.harris;
  const int margin = std::max(harris.border_px, harris.nms_radius_px + harris.block_size / 2 +
                                                    harris.aperture_size / 2 + 2);
  for (int cy = 0; cy < rows; ++cy) {
    for (int cx = 0; cx < cols; ++cx) {
      const std::size_t cell = static_cast<std::size_t>(cy * cols + cx);
      int& count = cell_count_[cell];
      if (count >= per_cell || frame_index_ < cell_retry_frame_[cell]) continue;
      // Pixels x with floor(x·cols/width) == cx: [ceil(cx·w/cols), ceil((cx+1)·w/cols)).
      const int x0 = (cx * left.cols + cols - 1) / cols;
      const int x1 = ((cx + 1) * left.cols + cols - 1) / cols;
      const int y0 = (cy * left.rows + rows - 1) / rows;
      const int y1 = ((cy + 1) * left.rows + rows - 1) / rows;
      const cv::Rect roi =
          cv::Rect(x0 - margin, y0 - margin, x1 - x0 + 2 * margin, y1 - y0 + 2 * margin) &
          cv::Rect(0, 0, left.cols, left.rows);
      const std::vector<perception::Corner> corners =
          perception::DetectHarrisCorners(left(roi), harris);  // strongest first
      for (const perception::Corner& corner : corners) {
        const cv::Point2f p(corner.position.x + static_cast<float>(roi.x),
                            corner.position.y + static_cast<float>(roi.y));
        if (cell_of(p) != cell) continue;
        // The ROI's border test is the image's only where the ROI touches the image edge.
        if (p.x < static_cast<float>(harris.border_px) ||
            p.y < static_cast<float>(harris.border_px) ||
            p.x > static_cast<float>(left.cols - 1 - harris.border_px) ||
            p.y > static_cast<float>(left.rows - 1 - harris.border_px)) {
          continue;
        }
        const int x = std::clamp(static_cast<int>(std::lround(p.x)), 0, left.cols - 1);
        const int y = std::clamp(static_cast<int>(std::lround(p.y)), 0, left.rows - 1);
        if (occupancy_.at<unsigned char>(y, x)) continue;
        const perception::StereoMatch m = matcher_.Match(left, right, p);
        if (!m.valid()) continue;
        const Eigen::Vector3d p_cam = TriangulateCorrected(p.x, p.y, m.disparity_px);
        if (!UsablePoint(p_cam)) continue;
        features->points.push_back(p);
        features->p_cam.push_back(p_cam);
        features->disparity.push_back(m.disparity_px);
        occupy(p);
        if (++count >= per_cell) break;
      }
      // Exhausted (too little texture, or every corner taken): look again later.
      if (count < per_cell)
        cell_retry_frame_[cell] = frame_index_ + options_.exhausted_cell_retry_frames;
    }
  }
}

void StereoVisualOdometry::CheckInput(const cv::Mat& left, const cv::Mat& right, double t_s) const {
  if (left.empty() || right.empty() || left.type() != CV_8UC1 || right.type() != CV_8UC1 ||
      left.size() != right.size()) {
    throw std::invalid_argument(
        "StereoVisualOdometry::Process: needs two non-empty CV_8UC1 images of one size");
  }
  if (!std::isfinite(t_s) || (has_previous_ && t_s < last_t_s_)) {
    throw std::invalid_argument("StereoVisualOdometry::Process: time " + std::to_string(t_s) +
                                " s is not finite or decreases (last " + std::to_string(last_t_s_) +
                                " s)");
  }
  if (has_previous_ && left.size() != image_size_) {
    throw std::invalid_argument("StereoVisualOdometry::Process: image size changed from " +
                                std::to_string(image_size_.width) + "x" +
                                std::to_string(image_size_.height) + " to " +
                                std::to_string(left.cols) + "x" + std::to_string(left.rows));
  }
}

VoFrameResult StereoVisualOdometry::Process(const cv::Mat& left, const cv::Mat& right, double t_s,
                                            const Eigen::Matrix3d* R_prev_curr_prior) {
  CheckInput(left, right, t_s);
  const Frame frame{left, right, t_s, R_prev_curr_prior};
  VoFrameResult result;
  result.t_s = t_s;
  tracker_.BuildPyramid(left, &curr_pyramid_);
  curr_.clear();
  if (!has_previous_) return StartAfresh(frame, &result);

  const int min_inliers = options_.min_inliers;
  const std::size_t n = prev_.size();
  if (n < static_cast<std::size_t>(min_inliers)) {
    return Fail(frame,
                {VoStatus::kTooFewFeatures, "only " + std::to_string(n) +
                                                " features in the previous frame (need " +
                                                std::to_string(min_inliers) + ")"},
                &result);
  }
  // 1. Track the previous frame's features into the current left image.
  result.tracked = TrackFeatures(left.size());
  // 2. Stereo-match the tracked points: the 3-D–3-D correspondences.
  result.matched = MatchTrackedFeatures(left, right);
  if (result.matched < min_inliers) {
    return Fail(
        frame,
        {VoStatus::kTooFewFeatures, std::to_string(result.matched) + " of " + std::to_string(n) +
                                        " features tracked and stereo-matched (need " +
                                        std::to_string(min_inliers) + ")"},
        &result);
  }
  // 3–4. RANSAC, refit, refinement and re-selection of the inliers.
  if (std::optional<Failure> failure = EstimateMotion(result.matched)) {
    return Fail(frame, std::move(*failure), &result);
  }
  // 4b. Vet the motion against the platform's bounds (a second consensus if need be).
  if (std::optional<Failure> failure = VetMotion(frame, &result)) {
    return Fail(frame, std::move(*failure), &result);
  }
  EstimateCovariance(frame, &result);
  AcceptMotion(frame, &result);
  // 5. Carry the inliers to the next frame; fill the grid's empty cells.
  CarryInliers();
  if (options_.estimate_disparity_offset) UpdateDisparityOffset();
  Replenish(left, right, &curr_);
  return Finish(frame, &result);
}

int StereoVisualOdometry::TrackFeatures(const cv::Size& image_size) {
  // LK starts where the last motion puts each point, so that large image motions stay
  // within its capture range.
  const std::size_t n = prev_.size();
  bool use_guess = false;
  if (options_.use_motion_prior && last_motion_valid_) {
    use_guess = true;
    tracked_points_.resize(n);
    const float max_x = static_cast<float>(image_size.width - 1),
                max_y = static_cast<float>(image_size.height - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d p = last_T_curr_prev_ * prev_.p_cam[i];
      cv::Point2f guess = prev_.points[i];
      if (p.z() > 1e-3) {
        const Eigen::Vector3d z = camera_.Project(p);
        guess = cv::Point2f(std::clamp(static_cast<float>(z.x()), 0.0f, max_x),
                            std::clamp(static_cast<float>(z.y()), 0.0f, max_y));
      }
      tracked_points_[i] = guess;
    }
  }
  return tracker_.Track(prev_pyramid_, curr_pyramid_, prev_.points, &tracked_points_,
                        &track_status_, use_guess);
}

int StereoVisualOdometry::MatchTrackedFeatures(const cv::Mat& left, const cv::Mat& right) {
  const std::size_t n = prev_.size();
  new_points_.clear();
  correspondence_feature_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (track_status_[i] != perception::TrackStatus::kTracked) continue;
    new_points_.push_back(tracked_points_[i]);
    correspondence_feature_.push_back(static_cast<int>(i));
  }
  matcher_.Match(left, right, new_points_, &matches_);
  correspondences_.clear();
  std::size_t kept = 0;
  for (std::size_t j = 0; j < new_points_.size(); ++j) {
    if (!matches_[j].valid()) continue;
    const int i = correspondence_feature_[j];
    const cv::Point2f& q = new_points_[j];
    const float d = matches_[j].disparity_px;
    MotionCorrespondence c;
    const auto k = static_cast<std::size_t>(i);
    const cv::Point2f& q_prev = prev_.points[k];
    const double d_prev = prev_.disparity[k];
    c.p_prev = options_.estimate_disparity_offset ? TriangulateCorrected(q_prev.x, q_prev.y, d_prev)
                                                  : prev_.p_cam[k];
    c.p_curr = TriangulateCorrected(q.x, q.y, d);
    if (!UsablePoint(c.p_prev) || !UsablePoint(c.p_curr)) continue;
    c.z_curr = Eigen::Vector3d(q.x, q.y, q.x - (d + disparity_offset_px_));
    c.z_prev = Eigen::Vector3d(q_prev.x, q_prev.y, q_prev.x - (d_prev + disparity_offset_px_));
    correspondences_.push_back(c);
    new_points_[kept++] = q;  // compacted: new_points_[k] belongs to correspondence k
  }
  return static_cast<int>(correspondences_.size());
}

std::optional<StereoVisualOdometry::Failure> StereoVisualOdometry::EstimateMotion(int matched) {
  EstimateStereoMotion(correspondences_, {}, camera_, motion_options_, rng_, &motion_);
  const std::string of_matched = " of " + std::to_string(matched) + " correspondences (need " +
                                 std::to_string(options_.min_inliers) + ")";
  switch (motion_.status) {
    case StereoMotionStatus::kOk:
      return std::nullopt;
    case StereoMotionStatus::kTooFewCorrespondences:  // Process checks this first
      return Failure{VoStatus::kTooFewFeatures, std::to_string(matched) + of_matched};
    case StereoMotionStatus::kDegenerate:
      return Failure{VoStatus::kRansacFailed, "every RANSAC sample of " + std::to_string(matched) +
                                                  " correspondences was degenerate"};
    case StereoMotionStatus::kTooFewConsensusInliers:
      return Failure{
          VoStatus::kTooFewInliers,
          "RANSAC found " + std::to_string(motion_.ransac.inliers) + " inliers" + of_matched};
    case StereoMotionStatus::kTooFewRefinedInliers:
      return Failure{
          VoStatus::kTooFewInliers,
          "refined motion keeps " + std::to_string(motion_.inliers) + " inliers" + of_matched};
  }
  return Failure{VoStatus::kTooFewInliers, "unknown motion status"};
}

std::optional<std::string> StereoVisualOdometry::ExceedsFrameBounds(
    const Eigen::Isometry3d& T) const {
  const double moved_m = T.translation().norm();
  const double turned_deg = units::Degrees(geometry::RotationAngle(T.linear()));
  if (moved_m > options_.max_translation_per_frame_m ||
      turned_deg > options_.max_rotation_per_frame_deg) {
    char reason[256];
    std::snprintf(reason, sizeof(reason),
                  "motion of %.3f m and %.1f deg exceeds the per-frame bounds (%.3f m, %.1f deg)",
                  moved_m, turned_deg, options_.max_translation_per_frame_m,
                  options_.max_rotation_per_frame_deg);
    return std::string(reason);
  }
  return std::nullopt;
}

std::optional<std::string> StereoVisualOdometry::BreaksDynamics(
    const Eigen::Isometry3d& T, const Frame& frame, const Eigen::Isometry3d& predicted) const {
  char reason[256];
  if (frame.R_prev_curr_prior) {
    // T maps prev to curr: its rotation times the prior's (prev from curr) is the error.
    const double error_deg =
        units::Degrees(geometry::RotationAngle(T.linear() * *frame.R_prev_curr_prior));
    if (error_deg > options_.max_rotation_prior_error_deg) {
      std::snprintf(reason, sizeof(reason),
                    "rotation departs from the prior's by %.2f deg (bound %.2f)", error_deg,
                    options_.max_rotation_prior_error_deg);
      return std::string(reason);
    }
  }
  if (!last_motion_valid_) return std::nullopt;
  const double dt = frame.t_s - last_t_s_;
  const Eigen::Isometry3d change = predicted.inverse() * T;
  const double change_m = change.translation().norm();
  const double change_deg = units::Degrees(geometry::RotationAngle(change.linear()));
  const double bound_m = options_.max_acceleration_mps2 * dt * dt;
  const double bound_deg = frame.R_prev_curr_prior
                               ? std::numeric_limits<double>::infinity()
                               : options_.max_angular_acceleration_dps2 * dt * dt;
  if (change_m > bound_m || change_deg > bound_deg) {
    std::snprintf(reason, sizeof(reason),
                  "motion departs from the constant-velocity prediction by %.3f m and %.2f deg "
                  "(dynamics bounds over %.3f s: %.3f m, %.2f deg)",
                  change_m, change_deg, dt, bound_m, bound_deg);
    return std::string(reason);
  }
  return std::nullopt;
}

std::optional<StereoVisualOdometry::Failure> StereoVisualOdometry::VetMotion(
    const Frame& frame, VoFrameResult* result) {
  const double dt = frame.t_s - last_t_s_;
  const Eigen::Isometry3d predicted = ContinuedMotion(last_T_curr_prev_, last_motion_dt_s_, dt);
  if (std::optional<std::string> reason = ExceedsFrameBounds(motion_.T_curr_prev)) {
    return Failure{VoStatus::kImplausibleMotion, std::move(*reason)};
  }
  const std::optional<std::string> broken = BreaksDynamics(motion_.T_curr_prev, frame, predicted);
  if (!broken) return std::nullopt;

  // RANSAC's consensus is not a motion the platform can make (points on a moving
  // object, say): the consensus of the other correspondences may be.
  candidate_mask_.resize(correspondences_.size());
  for (std::size_t j = 0; j < correspondences_.size(); ++j) {
    candidate_mask_[j] = motion_.inlier_mask[j] ? 0 : 1;
  }
  EstimateStereoMotion(correspondences_, candidate_mask_, camera_, motion_options_, rng_, &motion_);
  const bool recovered = motion_.ok() && !ExceedsFrameBounds(motion_.T_curr_prev) &&
                         !BreaksDynamics(motion_.T_curr_prev, frame, predicted);
  if (!recovered) {
    return Failure{VoStatus::kInconsistentMotion,
                   "RANSAC's " + *broken + "; the other " + std::to_string(motion_.candidates) +
                       " correspondences' consensus (" + std::to_string(motion_.ransac.inliers) +
                       " inliers) does not keep within them either"};
  }
  result->dynamics_constrained = true;
  return std::nullopt;
}

void StereoVisualOdometry::EstimateCovariance(const Frame& frame, VoFrameResult* result) {
  double offset_std_px = 0.0;  // the disparity offset's spread as a consider parameter
  if (options_.covariance_disparity_offset) {
    offset_std_px = options_.estimate_disparity_offset
                        ? std::sqrt(disparity_offset_var_px2_)
                        : options_.calibration_disparity_offset_std_px;
  }
  MotionCovariance covariance =
      EstimateMotionCovariance(correspondences_, motion_.inlier_mask, camera_, motion_.T_curr_prev,
                               options_.refinement.huber_px, offset_std_px);
  result->image_noise_px = covariance.image_noise_px;
  if (!covariance.valid) return;
  if (options_.rotation_prior_in_estimate && frame.R_prev_curr_prior) {
    const double dt = frame.t_s - last_t_s_;
    const double bias = options_.rotation_prior_bias_std_radps * dt;
    const double noise = options_.rotation_prior_noise_density;
    RotationPrior prior;
    prior.R_prev_curr = *frame.R_prev_curr_prior;
    prior.std_rad = std::sqrt(bias * bias + noise * noise * dt);
    if (prior.std_rad > 0.0) {
      AddRotationPrior(prior, &covariance, &motion_.T_curr_prev);
      result->rotation_prior_applied = true;
    }
  }
  result->covariance = covariance.covariance;
  result->covariance_valid = true;
}

void StereoVisualOdometry::AcceptMotion(const Frame& frame, VoFrameResult* result) {
  const Eigen::Isometry3d& T_curr_prev = motion_.T_curr_prev;
  result->status = VoStatus::kOk;
  result->inliers = motion_.inliers;
  result->reprojection_rms_px = motion_.refinement.final_rms_px;
  result->T_prev_curr = T_curr_prev.inverse();
  T_world_cam_ = T_world_cam_ * result->T_prev_curr;
  last_T_curr_prev_ = T_curr_prev;
  last_motion_dt_s_ = frame.t_s - last_t_s_;
  last_motion_valid_ = true;
}

void StereoVisualOdometry::UpdateDisparityOffset() {
  disparity_offset_var_px2_ +=
      options_.disparity_offset_walk_px * options_.disparity_offset_walk_px;
  const DisparityOffsetMeasurement m =
      MeasureDisparityOffset(correspondences_, motion_.inlier_mask, camera_, motion_.T_curr_prev,
                             options_.refinement.huber_px);
  if (!m.valid) return;
  const double gain = disparity_offset_var_px2_ / (disparity_offset_var_px2_ + m.variance_px2);
  disparity_offset_px_ += gain * m.offset_px;
  disparity_offset_var_px2_ *= 1.0 - gain;
}

void StereoVisualOdometry::CarryInliers() {
  for (std::size_t j = 0; j < correspondences_.size(); ++j) {
    if (!motion_.inlier_mask[j]) continue;
    curr_.points.push_back(new_points_[j]);
    curr_.p_cam.push_back(correspondences_[j].p_curr);
    const Eigen::Vector3d& z = correspondences_[j].z_curr;
    curr_.disparity.push_back(static_cast<float>(z.x() - z.z() - disparity_offset_px_));
  }
}

VoFrameResult StereoVisualOdometry::StartAfresh(const Frame& frame, VoFrameResult* result) {
  std::fill(cell_retry_frame_.begin(), cell_retry_frame_.end(), 0);
  result->status = VoStatus::kFirstFrame;
  T_world_cam_ = Eigen::Isometry3d::Identity();
  Replenish(frame.left, frame.right, &curr_);
  return Finish(frame, result);
}

VoFrameResult StereoVisualOdometry::Fail(const Frame& frame, Failure failure,
                                         VoFrameResult* result) {
  std::fill(cell_retry_frame_.begin(), cell_retry_frame_.end(), 0);  // search everywhere
  result->status = failure.status;
  result->reason = std::move(failure.reason);
  result->T_prev_curr = Eigen::Isometry3d::Identity();
  result->inliers = 0;
  last_motion_valid_ = false;
  curr_.clear();  // start afresh: detect everything in this frame
  Replenish(frame.left, frame.right, &curr_);
  return Finish(frame, result);
}

VoFrameResult StereoVisualOdometry::Finish(const Frame& frame, VoFrameResult* result) {
  ++frame_index_;
  std::swap(prev_, curr_);
  std::swap(prev_pyramid_, curr_pyramid_);
  has_previous_ = true;
  last_t_s_ = frame.t_s;
  image_size_ = frame.left.size();
  result->T_world_cam = T_world_cam_;
  result->features = static_cast<int>(prev_.size());
  result->disparity_offset_px = disparity_offset_px_;  // failed frames keep the estimate
  return *result;
}

}  // namespace trackbed::estimation
