// Repeat 3D: milestone-relative localization, steering and feature recovery (Diosi et
// al. 2007, as Choi & Ha 2011 §III describe it; docs/teach_repeat.md).
//
// Per frame, for the active milestone (3-D points p_first of its features in its first
// camera's frame, and its last camera T_first_last, from teaching):
//   1. Track: the milestone's features are tracked by KLT from the previous image (started
//      from the key image when the milestone became active, as in 2D).
//   2. Pose, the paper's way: the essential matrix between the milestone's first image
//      and the current one (5-point RANSAC, cv::findEssentialMat + cv::recoverPose),
//      triangulation of the inliers at unit baseline, and the scale made consistent with
//      the milestone's reconstruction by the ratio of corresponding 3-D points
//      (ScaleRatio: median |p_first| / |p_unit|). The metric T_first_cam follows.
//      When the image motion is too small for the essential matrix (median parallax <
//      min_parallax_px: at the start of every milestone the robot stands near the key
//      image, and the epipolar geometry degenerates) the previous frame's pose is used
//      instead.
//   3. Refinement (ours): starting from that pose, cv::solvePnP (Levenberg–Marquardt)
//      minimises the reprojection error of the milestone's 3-D points in the current
//      image over the tracked features (gated by gate_px), twice, dropping features
//      farther than max_reprojection_px in between. The milestone's points are metric
//      and fixed, so this is well-posed at any baseline; it also makes "reprojection of the
//      milestone features into the current image" (the paper's fig. 2) consistent with
//      the pose. A tracked feature that ends farther than max_reprojection_px from its
//      reprojection has slid off its point (onto an occluder's edge, say): it is lost.
//   4. Recovery (Diosi et al.; Choi & Ha fig. 5): every lost feature whose reprojection
//      falls inside the image is searched for: its stored patch (last teach image) and
//      the key image's patch around it are compared (ZNCC, SearchPatch) with the current
//      image within search_radius_px of the reprojection. While an occluder covers the
//      spot nothing matches; once it has passed, the best ZNCC >= min_zncc brings the
//      feature back at the matched position, and KLT tracks it on from the next frame.
//   5. Steering (ours; the paper does not give its control law). The camera's lateral
//      offset y [m] (> 0 left of the taught segment from the first to the last milestone
//      camera) and heading error θ [rad] (> 0 turned left) give
//          ω = −v · (y / L² + 2 θ / L),   clamped to ±max_yaw_rate_radps,
//      with forward speed v constant. With ẏ = v sin θ ≈ v θ and θ̇ = ω this is, per
//      metre travelled, y'' + (2/L) y' + (1/L²) y = 0: a critically damped approach to
//      the taught path over the distance scale L (`convergence_distance_m`),
//      independent of the speed. On a taught curve the reference heading turns by
//      κ = Δψ / length per metre (the milestone's T_first_last), so the law adds the
//      feed-forward v·κ: without it the path's yaw rate must come from a standing error,
//      y/L² + 2θ/L = κ (on the lab's 1.5 m radius and L = 1 m: 0.67 m, or θ = 19°), and
//      the repeat cuts the curve wide.
//   6. Switching: when the along-track position passes switch_progress (1 = the last
//      teach camera of the milestone), the next milestone becomes active: its features
//      are found by KLT from its key image, starting at the reprojection of its 3-D
//      points from the pose carried over (T_next_cam = T_first_last⁻¹ · T_first_cam).
// A milestone without a reconstruction (too little baseline in teaching) is followed by
// the 2D funnel-lane vote (funnel_lane_vote.h) and switched by the 2D error minimum
// (milestone_switch.h);
// so is a frame whose pose cannot be estimated (RepeatCommand::fallback_2d).
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/common/units.h"
#include "trackbed/perception/feature_tracker.h"
#include "trackbed/teach_repeat/milestone_repeater.h"
#include "trackbed/teach_repeat/teach_map.h"
#include "trackbed/teach_repeat/teach_repeat.h"
#include "trackbed/teach_repeat/teach_repeat_geometry.h"

namespace trackbed::teach_repeat {

/// The yaw rate of the 3D path-following law (see the file comment) for lateral offset
/// `lateral_m` and heading error `heading_rad` at forward speed `v_mps`, clamped to
/// ±max_yaw_rate_radps (> 0); `curvature_radpm` is the taught path's heading change per
/// metre [rad/m] (> 0 turning left), fed forward.
double PathFollowingYawRate(double lateral_m, double heading_rad, double v_mps,
                            double convergence_distance_m, double max_yaw_rate_radps,
                            double curvature_radpm = 0.0);

/// Options of MilestoneLocalizer3d.
struct Localizer3dOptions {
  /// Constant forward speed [m/s], > 0 (Choi & Ha's lab repeat: 0.05 m/s). Not a key of
  /// this struct: a run sets it from `teach_repeat.repeat_speed_mps`, which both
  /// repeaters share.
  double forward_speed_mps = 0.05;
  /// Largest |yaw rate| [rad/s], > 0 (Choi & Ha's lab repeat: 4°/s). Not a key of this
  /// struct: a run sets it from `teach_repeat.repeat_turn_rate_deg_s`.
  double max_yaw_rate_radps = units::Radians(4.0);
  /// Distance scale L of the steering law [m], > 0 (see the file comment).
  double convergence_distance_m = 1.0;
  /// Feed the taught curvature of the milestone forward into the steering law (file
  /// comment, step 5).
  bool curvature_feed_forward = true;
  /// Along-track position that switches to the next milestone, in (0, 2] (1 = the
  /// milestone's last teach camera).
  double switch_progress = 1.0;
  /// Milestones passed in one frame at most, >= 1: after a switch the next milestone's
  /// pose is estimated at once, and if the robot is already past it too (milestones of
  /// one to three images, cut densely in curves) it switches again.
  int max_switches_per_frame = 3;
  /// Fewer tracked features than this is "too few": the robot goes straight, >= 1.
  int min_features = 8;
  /// Consecutive frames with too few features before the repeat is lost, >= 1.
  int lost_patience_frames = 20;
  /// Milestone the repeat starts at (the robot stands near its key image), >= 0.
  int start_milestone = 0;
  /// KLT tracking of the milestone features (`tracker.*`, perception/feature_tracker.h).
  perception::FeatureTrackerOptions tracker = DefaultRepeatTrackerOptions();
  /// Essential matrix between the milestone's first image and the current one.
  TwoViewOptions two_view;
  /// The essential matrix is used only from this median image motion on [px], >= 0.
  double min_parallax_px = 4.0;
  /// Features farther than this from their reprojection by the initial pose are left
  /// out of the refinement [px], > 0.
  double gate_px = 15.0;
  /// After refinement, tracked features farther than this from their reprojection are
  /// lost [px], > 0.
  double max_reprojection_px = 2.0;
  /// Fewer features for the refinement than this and the frame has no pose, >= 4.
  int min_pose_features = 8;
  /// Recovery search radius around a lost feature's reprojection [px], >= 0.
  int search_radius_px = 5;
  /// ZNCC that recovers a feature, in (0, 1].
  double min_zncc = 0.85;
  /// Patches and windows flatter than this standard deviation [grey levels] match
  /// nothing, >= 0.
  double min_patch_stddev = 4.0;
  /// The 2D fallback's vote threshold, switch hysteresis and shortest milestone
  /// (FunnelLaneOptions' min_net_vote, switch_hysteresis_px, min_frames_per_milestone).
  double fallback_min_net_vote = 0.1;
  double fallback_switch_hysteresis_px = 1.0;
  int fallback_min_frames_per_milestone = 3;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `teach_repeat.localizer_3d`), read and written by the config archive
  /// (trackbed/common/archive.h); the speeds are keys elsewhere (above).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("convergence_distance_m", &convergence_distance_m);
    a->Visit("curvature_feed_forward", &curvature_feed_forward);
    a->Visit("switch_progress", &switch_progress);
    a->Visit("max_switches_per_frame", &max_switches_per_frame);
    a->Visit("min_features", &min_features);
    a->Visit("lost_patience_frames", &lost_patience_frames);
    a->Visit("start_milestone", &start_milestone);
    a->Visit("tracker", &tracker);
    a->Visit("two_view", &two_view);
    a->Visit("min_parallax_px", &min_parallax_px);
    a->Visit("gate_px", &gate_px);
    a->Visit("max_reprojection_px", &max_reprojection_px);
    a->Visit("min_pose_features", &min_pose_features);
    a->Visit("search_radius_px", &search_radius_px);
    a->Visit("min_zncc", &min_zncc);
    a->Visit("min_patch_stddev", &min_patch_stddev);
    a->Visit("fallback_min_net_vote", &fallback_min_net_vote);
    a->Visit("fallback_switch_hysteresis_px", &fallback_switch_hysteresis_px);
    a->Visit("fallback_min_frames_per_milestone", &fallback_min_frames_per_milestone);
  }
};

/// The 3D repeat (see the file comment). Stateful; not copyable.
class MilestoneLocalizer3d : public MilestoneRepeater {
 public:
  /// Throws OptionError for invalid options, std::invalid_argument for a map without
  /// milestones or a start milestone beyond it.
  MilestoneLocalizer3d(TeachMap map, const Localizer3dOptions& options = {});

  const char* method() const override { return "3d"; }
  const Localizer3dOptions& options() const { return options_; }

  /// Reprojections of the active milestone's features into the last image (valid where
  /// the last frame had a pose and the point lay in front of the camera): for drawing
  /// the paper's fig. 3 and for tests.
  const std::vector<std::optional<cv::Point2f>>& predicted() const { return predicted_; }
  /// Whether each feature of the active milestone is tracked in the last image.
  std::vector<bool> tracked_mask() const;

 private:
  void RepeatFrame(const cv::Mat& gray, RepeatCommand* cmd) override;
  void MilestoneStarted(const Milestone& m) override;
  /// Steps 2–3 of the file comment; fills the pose fields of `cmd`.
  bool EstimatePose(RepeatCommand* cmd);
  /// Step 4; returns the number of counted losses recovered.
  int Recover(const cv::Mat& gray);
  /// Step 6, once: makes the next milestone active, its tracks started from the pose
  /// carried over when there is one, and estimates its pose (`pose_ok`, `offset`).
  /// Returns whether the robot is already past that milestone too.
  bool SwitchToNextMilestone(RepeatCommand* cmd, bool* pose_ok, PathOffset* offset);
  /// Step 5 (or the 2D vote without a pose) on the active milestone; fills the rest of
  /// `cmd`.
  void Steer(bool pose_ok, const PathOffset& offset, RepeatCommand* cmd);

  Localizer3dOptions options_;
  Eigen::Isometry3d T_first_cam_ = Eigen::Isometry3d::Identity();  // last pose estimate
  std::vector<cv::Mat> key_patches_;  // patches of the key image around first_px
  std::vector<std::optional<cv::Point2f>> predicted_;
};

}  // namespace trackbed::teach_repeat
