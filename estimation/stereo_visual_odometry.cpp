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

#include <Eigen/Cholesky>

#include "trackbed/common/option_error.h"
#include "trackbed/estimation/absolute_orientation.h"
#include "trackbed/estimation/constant_velocity.h"

namespace trackbed::estimation {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

/// Huber cost of a residual norm e with threshold k: e² inside, 2ke − k² outside.
double Huber(double e, double k) { return e <= k ? e * e : 2.0 * k * e - k * k; }

/// Cost of the masked correspondences under T (points behind the camera count as a
/// large constant, so a step that pushes points behind is not preferred).
double RobustCost(const std::vector<MotionCorrespondence>& c, const std::vector<int>& active,
                  const StereoCamera& camera, const Eigen::Isometry3d& T, double k,
                  double* sum_sq) {
  double cost = 0.0, sq = 0.0;
  for (int i : active) {
    const Eigen::Vector3d p = T * c[static_cast<std::size_t>(i)].p_prev;
    if (!(p.z() > 1e-6)) {
      cost += 1e6;
      continue;
    }
    const Eigen::Vector3d r = camera.Project(p) - c[static_cast<std::size_t>(i)].z_curr;
    sq += r.squaredNorm();
    cost += Huber(r.norm(), k);
  }
  if (sum_sq) *sum_sq = sq;
  return cost;
}

int CountInliers(const std::vector<MotionCorrespondence>& c, const StereoCamera& camera,
                 const Eigen::Isometry3d& T, double threshold_px,
                 std::vector<unsigned char>* mask) {
  int count = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const bool in = IsReprojectionInlier(camera, T, c[i], threshold_px);
    if (mask) (*mask)[i] = in ? 1 : 0;
    count += in ? 1 : 0;
  }
  return count;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Camera model and residuals.

StereoCamera StereoCamera::FromCalibration(const perception::StereoCalibration& calibration) {
  StereoCamera c;
  c.fx = calibration.fx();
  c.fy = calibration.fy();
  c.cx = calibration.cx();
  c.cy = calibration.cy();
  c.baseline_m = calibration.baseline_m();
  if (!(std::isfinite(c.fx) && c.fx > 0.0 && std::isfinite(c.fy) && c.fy > 0.0 &&
        std::isfinite(c.baseline_m) && c.baseline_m > 0.0 && std::isfinite(c.cx) &&
        std::isfinite(c.cy))) {
    throw std::invalid_argument(
        "StereoCamera::FromCalibration: needs fx, fy, baseline > 0 and finite cx, cy");
  }
  return c;
}

Eigen::Vector3d StereoCamera::Triangulate(double u, double v, double disparity_px) const {
  const double Z = fx * baseline_m / disparity_px;
  return {(u - cx) * Z / fx, (v - cy) * Z / fy, Z};
}

Eigen::Vector3d StereoCamera::Project(const Eigen::Vector3d& p) const {
  const double inv_z = 1.0 / p.z();
  return {fx * p.x() * inv_z + cx, fy * p.y() * inv_z + cy, fx * (p.x() - baseline_m) * inv_z + cx};
}

Eigen::Isometry3d ApplyIncrement(const MotionIncrement& delta, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d phi = delta.tail<3>();
  const double angle = phi.norm();
  const Eigen::Matrix3d dR = angle > 0.0 ? Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix()
                                         : Eigen::Matrix3d::Identity();
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = dR * T.linear();
  out.translation() = dR * T.translation() + delta.head<3>();
  return out;
}

Eigen::Vector3d StereoReprojectionResidual(const StereoCamera& camera,
                                           const Eigen::Isometry3d& T_curr_prev,
                                           const MotionCorrespondence& c,
                                           Eigen::Matrix<double, 3, 6>* J) {
  const Eigen::Vector3d p = T_curr_prev * c.p_prev;
  const Eigen::Vector3d r = camera.Project(p) - c.z_curr;
  if (J) {
    // ∂(u_l, v, u_r)/∂p for u = fx·X/Z + cx, v = fy·Y/Z + cy, u_r = fx·(X − b)/Z + cx,
    // times ∂p/∂δ = [I | −[p]×] (left increment: p ← Exp(φ)p + ρ ≈ p + ρ + φ × p).
    const double iz = 1.0 / p.z(), iz2 = iz * iz;
    Eigen::Matrix3d P;
    P << camera.fx * iz, 0.0, -camera.fx * p.x() * iz2,  //
        0.0, camera.fy * iz, -camera.fy * p.y() * iz2,   //
        camera.fx * iz, 0.0, -camera.fx * (p.x() - camera.baseline_m) * iz2;
    J->leftCols<3>() = P;
    J->rightCols<3>() = -P * Skew(p);
  }
  return r;
}

bool IsReprojectionInlier(const StereoCamera& camera, const Eigen::Isometry3d& T_curr_prev,
                          const MotionCorrespondence& c, double threshold_px) {
  const Eigen::Vector3d p = T_curr_prev * c.p_prev;
  if (!(p.z() > 1e-6)) return false;
  const Eigen::Vector3d r = camera.Project(p) - c.z_curr;
  const double t2 = threshold_px * threshold_px;
  const double v2 = r.y() * r.y();
  return r.x() * r.x() + v2 <= t2 && r.z() * r.z() + v2 <= t2;
}

// ---------------------------------------------------------------------------------------
// RANSAC.

void MotionRansacOptions::Validate() const {
  if (max_iterations < 1) {
    throw OptionError("max_iterations",
                      "must be >= 1 (got " + std::to_string(max_iterations) + ")");
  }
  if (!(std::isfinite(confidence) && confidence > 0.0 && confidence < 1.0)) {
    throw OptionError("confidence",
                      "must be in (0, 1) (got " + option_check::Describe(confidence) + ")");
  }
  option_check::Positive("threshold_px", threshold_px);
}

void EstimateMotionRansac(const std::vector<MotionCorrespondence>& correspondences,
                          const StereoCamera& camera, const MotionRansacOptions& options,
                          std::mt19937_64& rng, MotionRansacResult* result) {
  options.Validate();
  const std::size_t n = correspondences.size();
  result->success = false;
  result->T_curr_prev = Eigen::Isometry3d::Identity();
  result->inliers = 0;
  result->iterations = 0;
  result->inlier_mask.assign(n, 0);
  if (n < 3) return;

  std::vector<Eigen::Vector3d> src(3), dst(3);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  int best = -1;
  Eigen::Isometry3d best_T = Eigen::Isometry3d::Identity();
  int needed = options.max_iterations;
  const double log_failure = std::log(1.0 - options.confidence);
  for (int it = 0; it < needed; ++it) {
    ++result->iterations;
    std::size_t s[3];
    s[0] = pick(rng);
    do s[1] = pick(rng);
    while (s[1] == s[0]);
    do s[2] = pick(rng);
    while (s[2] == s[0] || s[2] == s[1]);
    for (int k = 0; k < 3; ++k) {
      src[static_cast<std::size_t>(k)] = correspondences[s[k]].p_prev;
      dst[static_cast<std::size_t>(k)] = correspondences[s[k]].p_curr;
    }
    const std::optional<SimilarityTransform> horn = HornAbsoluteOrientation(src, dst);
    if (!horn) continue;  // collinear sample
    const Eigen::Isometry3d T = horn->Rigid();
    const int count = CountInliers(correspondences, camera, T, options.threshold_px, nullptr);
    if (count > best) {
      best = count;
      best_T = T;
      // Adaptive stop (Fischler & Bolles 1981; Hartley & Zisserman §4.7.1).
      const double ratio = static_cast<double>(count) / static_cast<double>(n);
      const double p_good = ratio * ratio * ratio;
      if (p_good >= 1.0) {
        needed = it + 1;
      } else if (p_good > 0.0) {
        const double k = log_failure / std::log(1.0 - p_good);
        if (k < static_cast<double>(needed)) needed = static_cast<int>(std::ceil(k));
      }
    }
  }
  if (best < 0) return;
  result->success = true;
  result->T_curr_prev = best_T;
  result->inliers =
      CountInliers(correspondences, camera, best_T, options.threshold_px, &result->inlier_mask);

  // Refit on the inliers. Stereo depth noise dominates the 3-D error and grows as Z²
  // (σ_Z = Z²σ_d/(fx·b)), so each pair is weighted by the inverse variance of the
  // difference of its two depths, 1/(Z_prev⁴ + Z_curr⁴) (up to a constant).
  if (result->inliers >= 3) {
    src.clear();
    dst.clear();
    std::vector<double> weights;
    for (std::size_t i = 0; i < n; ++i) {
      if (!result->inlier_mask[i]) continue;
      src.push_back(correspondences[i].p_prev);
      dst.push_back(correspondences[i].p_curr);
      const double z0 = correspondences[i].p_prev.z(), z1 = correspondences[i].p_curr.z();
      weights.push_back(1.0 / (z0 * z0 * z0 * z0 + z1 * z1 * z1 * z1));
    }
    if (const auto refit = HornAbsoluteOrientation(src, dst, false, weights)) {
      const Eigen::Isometry3d T = refit->Rigid();
      const int count = CountInliers(correspondences, camera, T, options.threshold_px, nullptr);
      if (count >= result->inliers) {
        result->T_curr_prev = T;
        result->inliers =
            CountInliers(correspondences, camera, T, options.threshold_px, &result->inlier_mask);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// Reprojection refinement.

void MotionRefinementOptions::Validate() const {
  if (max_iterations < 0) {
    throw OptionError("max_iterations",
                      "must be >= 0 (got " + std::to_string(max_iterations) + ")");
  }
  option_check::Positive("huber_px", huber_px);
  option_check::Positive("min_step", min_step);
}

MotionRefinementResult RefineMotionReprojection(
    const std::vector<MotionCorrespondence>& correspondences,
    const std::vector<unsigned char>& mask, const StereoCamera& camera,
    const Eigen::Isometry3d& T_init, const MotionRefinementOptions& options) {
  options.Validate();
  if (!mask.empty() && mask.size() != correspondences.size()) {
    throw std::invalid_argument("RefineMotionReprojection: mask has " +
                                std::to_string(mask.size()) + " entries for " +
                                std::to_string(correspondences.size()) + " correspondences");
  }
  std::vector<int> active;
  active.reserve(correspondences.size());
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    if (mask.empty() || mask[i]) active.push_back(static_cast<int>(i));
  }
  MotionRefinementResult out;
  out.T_curr_prev = T_init;
  if (active.empty()) {
    out.converged = true;
    return out;
  }
  const double k = options.huber_px;
  const double norm = 1.0 / (3.0 * static_cast<double>(active.size()));
  double sum_sq = 0.0;
  double cost = RobustCost(correspondences, active, camera, out.T_curr_prev, k, &sum_sq);
  out.initial_rms_px = std::sqrt(sum_sq * norm);
  out.final_rms_px = out.initial_rms_px;

  double lambda = 1e-6;
  Eigen::Matrix<double, 3, 6> J;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    // Normal equations of the IRLS-weighted (Huber) Gauss–Newton step.
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    MotionIncrement g = MotionIncrement::Zero();
    for (int i : active) {
      const MotionCorrespondence& c = correspondences[static_cast<std::size_t>(i)];
      if (!((out.T_curr_prev * c.p_prev).z() > 1e-6)) continue;
      const Eigen::Vector3d r = StereoReprojectionResidual(camera, out.T_curr_prev, c, &J);
      const double e = r.norm();
      const double w = e <= k ? 1.0 : k / e;
      H.noalias() += w * J.transpose() * J;
      g.noalias() += w * J.transpose() * r;
    }
    ++out.iterations;
    // Levenberg–Marquardt: damp until the cost goes down.
    bool accepted = false;
    MotionIncrement delta = MotionIncrement::Zero();
    while (lambda < 1e8) {
      Eigen::Matrix<double, 6, 6> A = H;
      A.diagonal() += lambda * H.diagonal().cwiseMax(1e-12);
      delta = A.ldlt().solve(-g);
      if (!delta.allFinite()) {
        lambda *= 10.0;
        continue;
      }
      const Eigen::Isometry3d T_new = ApplyIncrement(delta, out.T_curr_prev);
      double sq_new = 0.0;
      const double cost_new = RobustCost(correspondences, active, camera, T_new, k, &sq_new);
      if (cost_new <= cost) {
        out.T_curr_prev = T_new;
        cost = cost_new;
        sum_sq = sq_new;
        lambda = std::max(lambda * 0.1, 1e-9);
        accepted = true;
        break;
      }
      lambda *= 10.0;
    }
    if (!accepted || delta.norm() < options.min_step) {
      out.converged = true;  // no step lowers the cost, or the step is negligible
      break;
    }
  }
  out.final_rms_px = std::sqrt(sum_sq * norm);
  return out;
}

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
  }
  return "unknown";
}

namespace {
StereoVisualOdometryOptions Validated(const StereoVisualOdometryOptions& options) {
  options.Validate();
  return options;
}

}  // namespace

StereoVisualOdometry::StereoVisualOdometry(const perception::StereoCalibration& calibration,
                                           const StereoVisualOdometryOptions& options)
    : camera_(StereoCamera::FromCalibration(calibration)),
      options_(Validated(options)),
      tracker_(options_.tracker),
      matcher_(options_.matcher),
      rng_(options_.seed) {}

void StereoVisualOdometry::Reset() {
  has_previous_ = false;
  prev_.clear();
  curr_.clear();
  T_world_cam_ = Eigen::Isometry3d::Identity();
  last_T_curr_prev_ = Eigen::Isometry3d::Identity();
  last_motion_valid_ = false;
  rng_.seed(options_.seed);
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
        const Eigen::Vector3d p_cam = camera_.Triangulate(p.x, p.y, m.disparity_px);
        if (!UsablePoint(p_cam)) continue;
        features->points.push_back(p);
        features->p_cam.push_back(p_cam);
        occupy(p);
        if (++count >= per_cell) break;
      }
      // Exhausted (too little texture, or every corner taken): look again later.
      if (count < per_cell)
        cell_retry_frame_[cell] = frame_index_ + options_.exhausted_cell_retry_frames;
    }
  }
}

VoFrameResult StereoVisualOdometry::Process(const cv::Mat& left, const cv::Mat& right, double t_s,
                                            const Eigen::Matrix3d* R_prev_curr_prior) {
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

  VoFrameResult result;
  result.t_s = t_s;
  tracker_.BuildPyramid(left, &curr_pyramid_);
  curr_.clear();

  const auto finish = [&]() {
    ++frame_index_;
    std::swap(prev_, curr_);
    std::swap(prev_pyramid_, curr_pyramid_);
    has_previous_ = true;
    last_t_s_ = t_s;
    image_size_ = left.size();
    result.T_world_cam = T_world_cam_;
    result.features = static_cast<int>(prev_.size());
    return result;
  };
  const auto fail = [&](VoStatus status, std::string reason) {
    std::fill(cell_retry_frame_.begin(), cell_retry_frame_.end(), 0);  // search everywhere
    result.status = status;
    result.reason = std::move(reason);
    result.T_prev_curr = Eigen::Isometry3d::Identity();
    result.inliers = 0;
    last_motion_valid_ = false;
    curr_.clear();  // start afresh: detect everything in this frame
    Replenish(left, right, &curr_);
    return finish();
  };

  if (!has_previous_) {
    std::fill(cell_retry_frame_.begin(), cell_retry_frame_.end(), 0);
    result.status = VoStatus::kFirstFrame;
    T_world_cam_ = Eigen::Isometry3d::Identity();
    Replenish(left, right, &curr_);
    return finish();
  }
  const int min_inliers = options_.min_inliers;
  const std::size_t n = prev_.size();
  if (n < static_cast<std::size_t>(min_inliers)) {
    return fail(VoStatus::kTooFewFeatures, "only " + std::to_string(n) +
                                               " features in the previous frame (need " +
                                               std::to_string(min_inliers) + ")");
  }

  // 1. Track, starting where the last motion puts each point.
  bool use_guess = false;
  if (options_.use_motion_prior && last_motion_valid_) {
    use_guess = true;
    tracked_points_.resize(n);
    const float max_x = static_cast<float>(left.cols - 1),
                max_y = static_cast<float>(left.rows - 1);
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
  result.tracked = tracker_.Track(prev_pyramid_, curr_pyramid_, prev_.points, &tracked_points_,
                                  &track_status_, use_guess);

  // 2. Stereo-match the tracked points in the current pair.
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
    c.p_prev = prev_.p_cam[static_cast<std::size_t>(i)];
    c.p_curr = camera_.Triangulate(q.x, q.y, d);
    if (!UsablePoint(c.p_prev) || !UsablePoint(c.p_curr)) continue;
    c.z_curr = Eigen::Vector3d(q.x, q.y, static_cast<double>(q.x) - static_cast<double>(d));
    correspondences_.push_back(c);
    new_points_[kept++] = q;  // compacted: new_points_[k] belongs to correspondence k
  }
  result.matched = static_cast<int>(correspondences_.size());
  if (result.matched < min_inliers) {
    return fail(VoStatus::kTooFewFeatures, std::to_string(result.matched) + " of " +
                                               std::to_string(n) +
                                               " features tracked and stereo-matched (need " +
                                               std::to_string(min_inliers) + ")");
  }

  // 3. RANSAC with Horn on 3-point samples (includes the refit on its inliers).
  EstimateMotionRansac(correspondences_, camera_, options_.ransac, rng_, &ransac_);
  if (!ransac_.success) {
    return fail(VoStatus::kRansacFailed, "every RANSAC sample of " +
                                             std::to_string(result.matched) +
                                             " correspondences was degenerate");
  }
  if (ransac_.inliers < min_inliers) {
    return fail(VoStatus::kTooFewInliers, "RANSAC found " + std::to_string(ransac_.inliers) +
                                              " inliers of " + std::to_string(result.matched) +
                                              " correspondences (need " +
                                              std::to_string(min_inliers) + ")");
  }

  // 4. Reprojection refinement from an initial motion and its inlier mask; re-select
  //    the inliers with the refined motion; refine again on them.
  const double threshold = options_.ransac.threshold_px;
  inlier_mask_.resize(correspondences_.size());
  const auto refine = [&](const Eigen::Isometry3d& T_init, const std::vector<unsigned char>& mask,
                          int* inliers) {
    MotionRefinementResult refined =
        RefineMotionReprojection(correspondences_, mask, camera_, T_init, options_.refinement);
    *inliers =
        CountInliers(correspondences_, camera_, refined.T_curr_prev, threshold, &inlier_mask_);
    if (*inliers >= min_inliers) {
      refined = RefineMotionReprojection(correspondences_, inlier_mask_, camera_,
                                         refined.T_curr_prev, options_.refinement);
      *inliers =
          CountInliers(correspondences_, camera_, refined.T_curr_prev, threshold, &inlier_mask_);
    }
    refined.T_curr_prev.linear() =
        Eigen::Quaterniond(refined.T_curr_prev.linear()).normalized().toRotationMatrix();
    return refined;
  };
  int inliers = 0;
  MotionRefinementResult refined = refine(ransac_.T_curr_prev, ransac_.inlier_mask, &inliers);
  if (inliers < min_inliers || !refined.T_curr_prev.matrix().allFinite()) {
    return fail(VoStatus::kTooFewInliers, "refined motion keeps " + std::to_string(inliers) +
                                              " inliers of " + std::to_string(result.matched) +
                                              " correspondences (need " +
                                              std::to_string(min_inliers) + ")");
  }

  // A motion the platform can make: within the per-frame bounds, and — when the last
  // frame had a motion — within the dynamics bounds of the constant-velocity prediction.
  const auto exceeds_bounds = [&](const Eigen::Isometry3d& T, char* reason, std::size_t size) {
    const double moved_m = T.translation().norm();
    const double turned_deg = Eigen::AngleAxisd(T.linear()).angle() * 180.0 / M_PI;
    if (moved_m > options_.max_translation_per_frame_m ||
        turned_deg > options_.max_rotation_per_frame_deg) {
      std::snprintf(reason, size,
                    "motion of %.3f m and %.1f deg exceeds the per-frame bounds (%.3f m, %.1f deg)",
                    moved_m, turned_deg, options_.max_translation_per_frame_m,
                    options_.max_rotation_per_frame_deg);
      return true;
    }
    return false;
  };
  const double dt = t_s - last_t_s_;
  const Eigen::Isometry3d predicted = ContinuedMotion(last_T_curr_prev_, last_motion_dt_s_, dt);
  const auto breaks_dynamics = [&](const Eigen::Isometry3d& T, char* reason, std::size_t size) {
    if (R_prev_curr_prior) {
      // T maps prev to curr: its rotation times the prior's (prev from curr) is the error.
      const double error_deg =
          Eigen::AngleAxisd(T.linear() * *R_prev_curr_prior).angle() * 180.0 / M_PI;
      if (error_deg > options_.max_rotation_prior_error_deg) {
        std::snprintf(reason, size, "rotation departs from the prior's by %.2f deg (bound %.2f)",
                      error_deg, options_.max_rotation_prior_error_deg);
        return true;
      }
    }
    if (!last_motion_valid_) return false;
    const Eigen::Isometry3d change = predicted.inverse() * T;
    const double change_m = change.translation().norm();
    const double change_deg = Eigen::AngleAxisd(change.linear()).angle() * 180.0 / M_PI;
    const double bound_m = options_.max_acceleration_mps2 * dt * dt;
    const double bound_deg = R_prev_curr_prior ? std::numeric_limits<double>::infinity()
                                               : options_.max_angular_acceleration_dps2 * dt * dt;
    if (change_m > bound_m || change_deg > bound_deg) {
      std::snprintf(reason, size,
                    "motion departs from the constant-velocity prediction by %.3f m and %.2f deg "
                    "(dynamics bounds over %.3f s: %.3f m, %.2f deg)",
                    change_m, change_deg, dt, bound_m, bound_deg);
      return true;
    }
    return false;
  };
  char reason[256];
  if (exceeds_bounds(refined.T_curr_prev, reason, sizeof(reason))) {
    return fail(VoStatus::kImplausibleMotion, reason);
  }
  if (breaks_dynamics(refined.T_curr_prev, reason, sizeof(reason))) {
    // RANSAC's consensus is not a motion the platform can make (points on a moving
    // object, say): the consensus of the other correspondences may be.
    const std::string ransac_reason = reason;
    rest_.clear();
    rest_index_.clear();
    for (std::size_t j = 0; j < correspondences_.size(); ++j) {
      if (inlier_mask_[j]) continue;
      rest_.push_back(correspondences_[j]);
      rest_index_.push_back(static_cast<int>(j));
    }
    int second = 0;
    bool recovered = false;
    if (rest_.size() >= static_cast<std::size_t>(min_inliers)) {
      EstimateMotionRansac(rest_, camera_, options_.ransac, rng_, &ransac_);
      second = ransac_.success ? ransac_.inliers : 0;
    }
    if (second >= min_inliers) {
      rest_mask_.assign(correspondences_.size(), 0);
      for (std::size_t k = 0; k < rest_.size(); ++k) {
        rest_mask_[static_cast<std::size_t>(rest_index_[k])] = ransac_.inlier_mask[k];
      }
      refined = refine(ransac_.T_curr_prev, rest_mask_, &inliers);
      recovered = inliers >= min_inliers && refined.T_curr_prev.matrix().allFinite() &&
                  !exceeds_bounds(refined.T_curr_prev, reason, sizeof(reason)) &&
                  !breaks_dynamics(refined.T_curr_prev, reason, sizeof(reason));
    }
    if (!recovered) {
      return fail(VoStatus::kInconsistentMotion,
                  "RANSAC's " + ransac_reason + "; the other " + std::to_string(rest_.size()) +
                      " correspondences' consensus (" + std::to_string(second) +
                      " inliers) does not keep within them either");
    }
    result.dynamics_constrained = true;
  }
  const Eigen::Isometry3d& T_curr_prev = refined.T_curr_prev;
  result.status = VoStatus::kOk;
  result.inliers = inliers;
  result.reprojection_rms_px = refined.final_rms_px;
  result.T_prev_curr = T_curr_prev.inverse();
  T_world_cam_ = T_world_cam_ * result.T_prev_curr;
  last_T_curr_prev_ = T_curr_prev;
  last_motion_dt_s_ = dt;
  last_motion_valid_ = true;

  // 5. Carry the inliers to the next frame; fill the grid's empty cells.
  for (std::size_t j = 0; j < correspondences_.size(); ++j) {
    if (!inlier_mask_[j]) continue;
    curr_.points.push_back(new_points_[j]);
    curr_.p_cam.push_back(correspondences_[j].p_curr);
  }
  Replenish(left, right, &curr_);
  return finish();
}

}  // namespace trackbed::estimation
