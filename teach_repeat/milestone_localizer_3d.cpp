// Repeat 3D: pose from the essential matrix and the milestone's 3-D points, steering,
// switching and feature recovery (see milestone_localizer_3d.h).
#include "trackbed/teach_repeat/milestone_localizer_3d.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "teach_repeat_tracks.h"
#include "trackbed/common/option_error.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/teach_repeat/funnel_lane_vote.h"

namespace trackbed::teach_repeat {
namespace {

cv::Point3d ToCv(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// T_cam_first as OpenCV's (rvec, tvec) and back.
void ToRvecTvec(const Eigen::Isometry3d& T, cv::Mat* rvec, cv::Mat* tvec) {
  cv::Mat R(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R.at<double>(r, c) = T.linear()(r, c);
  }
  cv::Rodrigues(R, *rvec);
  *tvec = (cv::Mat_<double>(3, 1) << T.translation().x(), T.translation().y(), T.translation().z());
}

Eigen::Isometry3d FromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = R.at<double>(r, c);
    T.translation()(r) = tvec.at<double>(r, 0);
  }
  return T;
}

/// Pixel distance between the reprojection of p_first by T_cam_first and `z`; +inf when the
/// point is behind the camera.
double ReprojectionError(const geometry::PinholeCamera& camera,
                         const Eigen::Isometry3d& T_cam_first, const Eigen::Vector3d& p_first,
                         const cv::Point2f& z) {
  const std::optional<cv::Point2d> q = ProjectPoint(camera, T_cam_first * p_first);
  if (!q) return std::numeric_limits<double>::infinity();
  return std::hypot(q->x - z.x, q->y - z.y);
}

/// Levenberg–Marquardt refinement of T_cam_first on the selected features.
bool RefinePnP(const geometry::PinholeCamera& camera, const Milestone& m,
               const std::vector<detail::FeatureTrack>& tracks, const std::vector<std::size_t>& sel,
               Eigen::Isometry3d* T_cam_first) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (std::size_t i : sel) {
    object.push_back(ToCv(m.features[i].p_first));
    image.emplace_back(tracks[i].position.x, tracks[i].position.y);
  }
  cv::Mat rvec, tvec;
  ToRvecTvec(*T_cam_first, &rvec, &tvec);
  if (!cv::solvePnP(object, image, cv::Mat(perception::CvCameraMatrix(camera)), cv::noArray(), rvec,
                    tvec,
                    /*useExtrinsicGuess=*/true, cv::SOLVEPNP_ITERATIVE)) {
    return false;
  }
  const Eigen::Isometry3d T = FromRvecTvec(rvec, tvec);
  if (!T.matrix().allFinite()) return false;
  *T_cam_first = T;
  return true;
}

/// The base's settings from validated options (the options are checked before the map).
MilestoneRepeaterSettings SettingsOf(const Localizer3dOptions& options) {
  options.Validate();
  MilestoneRepeaterSettings s;
  s.name = "MilestoneLocalizer3d";
  s.start_milestone = options.start_milestone;
  s.tracker = options.tracker;
  s.switch_hysteresis_px = options.fallback_switch_hysteresis_px;
  s.switch_error = SwitchError::kMeanOutward;
  s.remove_rotation = true;
  s.min_features = options.min_features;
  s.lost_patience_frames = options.lost_patience_frames;
  s.forward_speed_mps = options.forward_speed_mps;
  return s;
}

/// Guesses for the features of milestone `next` in the current image: the reprojections
/// of their 3-D points from the camera pose T_next_cam (their key-image positions where
/// a point lies behind the camera).
std::vector<cv::Point2f> ReprojectedGuesses(const geometry::PinholeCamera& camera,
                                            const Milestone& next,
                                            const Eigen::Isometry3d& T_next_cam) {
  const Eigen::Isometry3d T_cam_next = T_next_cam.inverse();
  std::vector<cv::Point2f> guesses;
  for (const MilestoneFeature& f : next.features) {
    const std::optional<cv::Point2d> q = ProjectPoint(camera, T_cam_next * f.p_first);
    guesses.push_back(q ? cv::Point2f(static_cast<float>(q->x), static_cast<float>(q->y))
                        : f.first_px);
  }
  return guesses;
}

}  // namespace

double PathFollowingYawRate(double lateral_m, double heading_rad, double v_mps,
                            double convergence_distance_m, double max_yaw_rate_radps,
                            double curvature_radpm) {
  const double L = convergence_distance_m;
  const double omega = v_mps * (curvature_radpm - lateral_m / (L * L) - 2.0 * heading_rad / L);
  return std::clamp(omega, -max_yaw_rate_radps, max_yaw_rate_radps);
}

void Localizer3dOptions::Validate() const {
  option_check::Positive("forward_speed_mps", forward_speed_mps);
  option_check::Positive("max_yaw_rate_radps", max_yaw_rate_radps);
  option_check::Positive("convergence_distance_m", convergence_distance_m);
  if (!(switch_progress > 0.0 && switch_progress <= 2.0)) {
    throw OptionError("switch_progress",
                      "must be in (0, 2] (got " + option_check::Describe(switch_progress) + ")");
  }
  option_check::AtLeast("max_switches_per_frame", max_switches_per_frame, 1);
  option_check::AtLeast("min_features", min_features, 1);
  option_check::AtLeast("lost_patience_frames", lost_patience_frames, 1);
  option_check::AtLeast("start_milestone", start_milestone, 0);
  option_check::Nested("tracker", tracker);
  option_check::Nested("two_view", two_view);
  option_check::NonNegative("min_parallax_px", min_parallax_px);
  option_check::Positive("gate_px", gate_px);
  option_check::Positive("max_reprojection_px", max_reprojection_px);
  option_check::AtLeast("min_pose_features", min_pose_features, 4);
  option_check::AtLeast("search_radius_px", search_radius_px, 0);
  if (!(min_zncc > 0.0 && min_zncc <= 1.0)) {
    throw OptionError("min_zncc",
                      "must be in (0, 1] (got " + option_check::Describe(min_zncc) + ")");
  }
  option_check::NonNegative("min_patch_stddev", min_patch_stddev);
  if (!(fallback_min_net_vote >= 0.0 && fallback_min_net_vote < 1.0)) {
    throw OptionError(
        "fallback_min_net_vote",
        "must be in [0, 1) (got " + option_check::Describe(fallback_min_net_vote) + ")");
  }
  option_check::NonNegative("fallback_switch_hysteresis_px", fallback_switch_hysteresis_px);
  option_check::AtLeast("fallback_min_frames_per_milestone", fallback_min_frames_per_milestone, 1);
}

MilestoneLocalizer3d::MilestoneLocalizer3d(TeachMap map, const Localizer3dOptions& options)
    : MilestoneRepeater(std::move(map), SettingsOf(options)), options_(options) {}

std::vector<bool> MilestoneLocalizer3d::tracked_mask() const {
  std::vector<bool> mask;
  for (const detail::FeatureTrack& t : tracks_->tracks()) mask.push_back(t.tracked);
  return mask;
}

void MilestoneLocalizer3d::MilestoneStarted(const Milestone& m) {
  const int s = map_.patch_size_px;
  key_patches_.resize(m.features.size());
  for (std::size_t i = 0; i < m.features.size(); ++i) {
    cv::getRectSubPix(m.key_image, cv::Size(s, s), m.features[i].first_px, key_patches_[i], CV_8U);
  }
  predicted_.assign(m.features.size(), std::nullopt);
}

bool MilestoneLocalizer3d::EstimatePose(RepeatCommand* cmd) {
  const Milestone& m = map_.milestones[static_cast<std::size_t>(milestone_)];
  const std::vector<detail::FeatureTrack>& tracks = tracks_->tracks();
  std::fill(predicted_.begin(), predicted_.end(), std::nullopt);
  std::vector<std::size_t> idx;
  std::vector<cv::Point2f> a, b;
  std::vector<Eigen::Vector3d> reference;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!tracks[i].tracked) continue;
    idx.push_back(i);
    a.push_back(m.features[i].first_px);
    b.push_back(tracks[i].position);
    reference.push_back(m.features[i].p_first);
  }
  if (static_cast<int>(idx.size()) < options_.min_pose_features) return false;

  // Step 2: essential matrix, triangulation at unit baseline, scale by the ratio of the
  // milestone's 3-D points to the unit-scale ones.
  Eigen::Isometry3d T_first_cam = T_first_cam_;
  std::vector<double> parallax;
  for (std::size_t k = 0; k < a.size(); ++k) {
    parallax.push_back(std::hypot(b[k].x - a[k].x, b[k].y - a[k].y));
  }
  std::nth_element(parallax.begin(),
                   parallax.begin() + static_cast<std::ptrdiff_t>(parallax.size() / 2),
                   parallax.end());
  const TwoViewGeometry g = parallax[parallax.size() / 2] >= options_.min_parallax_px
                                ? ReconstructTwoView(map_.camera, a, b, -1.0, options_.two_view)
                                : TwoViewGeometry{};
  if (g.ok) {
    const std::optional<double> ratio = ScaleRatio(reference, g.p_a, g.inlier);
    if (ratio) {
      T_first_cam = g.T_a_b;
      T_first_cam.translation() *= *ratio;
      cmd->essential_used = true;
      cmd->essential_inliers = g.inliers;
      cmd->scale_ratio = *ratio;
    }
  }

  // Step 3: refinement on the reprojection of the milestone's points.
  Eigen::Isometry3d T_cam_first = T_first_cam.inverse();
  std::vector<std::size_t> sel;
  for (std::size_t i : idx) {
    if (ReprojectionError(map_.camera, T_cam_first, m.features[i].p_first, tracks[i].position) <
        options_.gate_px) {
      sel.push_back(i);
    }
  }
  if (static_cast<int>(sel.size()) < options_.min_pose_features) {
    // The initial pose is far off (a repeat that starts away from the key image, say):
    // a robust PnP over all tracked features instead.
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    for (std::size_t i : idx) {
      object.push_back(ToCv(m.features[i].p_first));
      image.emplace_back(tracks[i].position.x, tracks[i].position.y);
    }
    cv::Mat rvec, tvec, inliers;
    if (!cv::solvePnPRansac(object, image, cv::Mat(perception::CvCameraMatrix(map_.camera)),
                            cv::noArray(), rvec, tvec, false, 200,
                            static_cast<float>(options_.max_reprojection_px), 0.99, inliers,
                            cv::SOLVEPNP_EPNP)) {
      return false;
    }
    T_cam_first = FromRvecTvec(rvec, tvec);
    sel.clear();
    for (std::size_t i : idx) {
      if (ReprojectionError(map_.camera, T_cam_first, m.features[i].p_first, tracks[i].position) <
          options_.gate_px) {
        sel.push_back(i);
      }
    }
    if (static_cast<int>(sel.size()) < options_.min_pose_features) return false;
  }
  if (!RefinePnP(map_.camera, m, tracks, sel, &T_cam_first)) return false;
  std::vector<std::size_t> keep;
  for (std::size_t i : sel) {
    if (ReprojectionError(map_.camera, T_cam_first, m.features[i].p_first, tracks[i].position) <
        options_.max_reprojection_px) {
      keep.push_back(i);
    }
  }
  if (static_cast<int>(keep.size()) < options_.min_pose_features) return false;
  if (!RefinePnP(map_.camera, m, tracks, keep, &T_cam_first)) return false;

  // Tracked features that disagree with their reprojection have slid off their points.
  // On a milestone's first frame they were never tracked properly: lost, not counted.
  double sum_sq = 0.0;
  int n = 0;
  for (std::size_t i : idx) {
    const double e =
        ReprojectionError(map_.camera, T_cam_first, m.features[i].p_first, tracks[i].position);
    if (e > options_.max_reprojection_px) {
      if (frames_in_milestone_ > 1) {
        tracks_->Lose(i);
      } else {
        tracks_->Forget(i);
      }
      continue;
    }
    sum_sq += e * e;
    ++n;
  }
  cmd->reprojection_rms_px = n > 0 ? std::sqrt(sum_sq / n) : 0.0;
  T_first_cam_ = T_cam_first.inverse();
  for (std::size_t i = 0; i < m.features.size(); ++i) {
    const std::optional<cv::Point2d> q =
        ProjectPoint(map_.camera, T_cam_first * m.features[i].p_first);
    if (q) predicted_[i] = cv::Point2f(static_cast<float>(q->x), static_cast<float>(q->y));
  }
  cmd->pose_valid = true;
  cmd->T_first_cam = T_first_cam_;
  return true;
}

int MilestoneLocalizer3d::Recover(const cv::Mat& gray) {
  const Milestone& m = map_.milestones[static_cast<std::size_t>(milestone_)];
  const int margin = map_.patch_size_px / 2 + options_.search_radius_px;
  const float max_x = static_cast<float>(gray.cols - 1 - margin);
  const float max_y = static_cast<float>(gray.rows - 1 - margin);
  int recovered = 0;
  for (std::size_t i = 0; i < m.features.size(); ++i) {
    if (tracks_->tracks()[i].tracked || !predicted_[i]) continue;
    const cv::Point2f q = *predicted_[i];
    if (q.x < margin || q.y < margin || q.x > max_x || q.y > max_y) continue;
    PatchMatch best = SearchPatch(gray, m.features[i].patch, q, options_.search_radius_px,
                                  options_.min_patch_stddev);
    const PatchMatch key =
        SearchPatch(gray, key_patches_[i], q, options_.search_radius_px, options_.min_patch_stddev);
    if (key.found && (!best.found || key.score > best.score)) best = key;
    if (!best.found || best.score < options_.min_zncc) continue;
    if (tracks_->Recover(i, best.position) == detail::Found::kRecovered) ++recovered;
  }
  return recovered;
}

void MilestoneLocalizer3d::RepeatFrame(const cv::Mat& gray, RepeatCommand* cmd) {
  const Milestone& m = map_.milestones[static_cast<std::size_t>(milestone_)];
  bool pose_ok = m.reconstructed && EstimatePose(cmd);
  if (pose_ok) cmd->recovered = Recover(gray);
  if (!pose_ok) std::fill(predicted_.begin(), predicted_.end(), std::nullopt);
  cmd->lost = tracks_->CommitLosses();  // still lost after the recovery attempt

  // Switching: by the along-track position when there is a pose, else by the 2D error
  // minimum (which is followed every frame, so that it is ready when the pose fails).
  const detail::FunnelFrame frame_2d =
      detail::EvaluateFunnel(map_.camera, m, tracks_->tracks(), /*bearing=*/true);
  const bool passed_2d = switch_->Update(frame_2d) &&
                         frames_in_milestone_ > options_.fallback_min_frames_per_milestone;
  bool passed = passed_2d;
  PathOffset offset;
  if (m.reconstructed && pose_ok) {
    offset = ComputePathOffset(T_first_cam_, m.T_first_last);
    passed = offset.progress >= options_.switch_progress;
  }
  lost_total_ += cmd->lost;
  recovered_total_ += cmd->recovered;
  for (int switches = 0; passed && switches < options_.max_switches_per_frame; ++switches) {
    if (milestone_ + 1 >= static_cast<int>(map_.milestones.size())) {
      Finish(cmd);
      return;
    }
    passed = SwitchToNextMilestone(cmd, &pose_ok, &offset);
  }
  Steer(pose_ok, offset, cmd);
}

bool MilestoneLocalizer3d::SwitchToNextMilestone(RepeatCommand* cmd, bool* pose_ok,
                                                 PathOffset* offset) {
  const Milestone& m = map_.milestones[static_cast<std::size_t>(milestone_)];
  const Milestone& next = map_.milestones[static_cast<std::size_t>(milestone_ + 1)];
  Eigen::Isometry3d T_next_cam = Eigen::Isometry3d::Identity();
  if (m.reconstructed && *pose_ok) {
    // The next milestone's first camera is this one's last.
    T_next_cam = m.T_first_last.inverse() * T_first_cam_;
  }
  const std::vector<cv::Point2f> guesses = next.reconstructed && m.reconstructed && *pose_ok
                                               ? ReprojectedGuesses(map_.camera, next, T_next_cam)
                                               : detail::ShiftedGuesses(m, tracks_->tracks(), next);
  StartMilestone(milestone_ + 1, guesses);
  T_first_cam_ = T_next_cam;
  cmd->switched = true;
  ++frames_in_milestone_;
  switch_->Update(detail::EvaluateFunnel(map_.camera, next, tracks_->tracks(), /*bearing=*/true));
  RepeatCommand fresh;  // the new milestone's pose, without loss counting
  *pose_ok = next.reconstructed && EstimatePose(&fresh);
  cmd->pose_valid = fresh.pose_valid;
  cmd->essential_used = fresh.essential_used;
  cmd->essential_inliers = fresh.essential_inliers;
  cmd->scale_ratio = fresh.scale_ratio;
  cmd->reprojection_rms_px = fresh.reprojection_rms_px;
  if (!*pose_ok) return false;
  *offset = ComputePathOffset(T_first_cam_, next.T_first_last);
  return offset->progress >= options_.switch_progress;
}

void MilestoneLocalizer3d::Steer(bool pose_ok, const PathOffset& offset, RepeatCommand* cmd) {
  const Milestone& m = map_.milestones[static_cast<std::size_t>(milestone_)];
  cmd->milestone = milestone_;
  cmd->features = static_cast<int>(tracks_->size());
  cmd->tracked = tracks_->tracked();
  cmd->features_lost = lost_total_;
  cmd->features_recovered = recovered_total_;
  if (pose_ok) {
    cmd->T_first_cam = T_first_cam_;
    cmd->lateral_offset_m = offset.lateral_m;
    cmd->heading_error_rad = offset.heading_rad;
    cmd->progress = offset.progress;
  }
  const detail::FunnelFrame frame =
      detail::EvaluateFunnel(map_.camera, m, tracks_->tracks(), /*bearing=*/true);
  cmd->votes_left = frame.tally.left;
  cmd->votes_right = frame.tally.right;
  cmd->votes_straight = frame.tally.straight;
  cmd->mean_error_px = switch_->error_px();

  if (GoStraightIfTooFewFeatures(cmd)) return;
  cmd->twist.v_mps = options_.forward_speed_mps;
  if (pose_ok) {
    const double curvature = options_.curvature_feed_forward && offset.segment_length_m >= 1e-3
                                 ? CameraHeading(m.T_first_last.linear()) / offset.segment_length_m
                                 : 0.0;
    cmd->twist.yaw_rate_radps = PathFollowingYawRate(
        offset.lateral_m, offset.heading_rad, options_.forward_speed_mps,
        options_.convergence_distance_m, options_.max_yaw_rate_radps, curvature);
  } else {
    cmd->fallback_2d = true;
    cmd->decision = DecideTurn(frame.tally, options_.fallback_min_net_vote);
    cmd->twist.yaw_rate_radps =
        static_cast<double>(static_cast<int>(cmd->decision)) * options_.max_yaw_rate_radps;
  }
}

}  // namespace trackbed::teach_repeat
