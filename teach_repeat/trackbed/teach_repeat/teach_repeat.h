// The repeat phase of visual teach & repeat: the types every repeater shares — its
// status, the funnel-lane vote, the per-frame command — and the Repeater interface. The
// repeaters are the 2D funnel-lane follower (Chen & Birchfield 2006,
// funnel_lane_controller.h) and the 3D milestone localizer (Diosi et al. 2007,
// milestone_localizer_3d.h), on a common base (milestone_repeater.h); MakeRepeater
// (repeater_factory.h) picks one by name.
//
// A repeater is fed the current left grey image once per camera frame and returns a body
// twist (constant forward speed, a yaw rate) and a status. It sees images only: no
// odometry, no ground truth. Per frame it
//   1. tracks the active milestone's features from the previous image into this one
//      (pyramidal KLT, forward–backward checked);
//   2. steers (2D: a vote over the funnel-lane rules; 3D: the pose relative to the
//      milestone, from the essential matrix and the milestone's 3-D points);
//   3. switches to the next milestone when this one is passed, starting the new
//      milestone's tracks by KLT from its key image into the current image.
// Feature losses are counted when a tracked feature is lost (KLT failure, forward–
// backward check, leaving the image, or — 3D — disagreeing with its reprojection) and
// not found again by patch matching in the same frame; recoveries when such a feature is
// found again in a later frame by patch matching (3D only). The caller measures
// per-place recovery from the cumulative counters (see teach_repeat_metrics.h).
#pragma once

#include <cstdint>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/common/skid_steer.h"
#include "trackbed/teach_repeat/teach_map.h"

namespace trackbed::teach_repeat {

/// Status of a repeat.
enum class RepeatStatus {
  kDriving,   ///< following the route (possibly briefly with too few features)
  kFinished,  ///< the last milestone was passed: the command is zero, and stays so
  kLost,      ///< too few features for longer than the patience: zero, and stays so
};
/// "driving", "finished", "lost".
const char* ToString(RepeatStatus status);

/// One feature's funnel-lane vote (Chen & Birchfield 2006; Choi & Ha 2011 eq. 1).
enum class TurnVote : std::int8_t { kLeft = 1, kStraight = 0, kRight = -1 };
/// "left", "straight", "right".
const char* ToString(TurnVote vote);

/// One repeat frame's output.
struct RepeatCommand {
  RepeatStatus status = RepeatStatus::kDriving;
  /// Forward speed [m/s] and yaw rate [rad/s] (> 0 turns left, counter-clockwise).
  kinematics::BodyTwist twist;
  int milestone = 0;                  ///< active milestone (after a switch in this frame)
  bool switched = false;              ///< a milestone switch happened in this frame
  bool switched_by_distance = false;  ///< that by the 2D distance bound, not the images
  int features = 0;                   ///< features of the active milestone
  int tracked = 0;                    ///< of those, tracked in this image
  /// Too few tracked features in this frame (< min_features): the command goes straight.
  bool too_few_features = false;
  /// The steering decision (2D, and 3D when falling back to the vote).
  TurnVote decision = TurnVote::kStraight;
  int votes_left = 0, votes_right = 0, votes_straight = 0;
  /// Mean x-error of the tracked features to the destination image [px], as the 2D
  /// milestone switch sees it (FunnelLaneOptions::switch_error; milestone_switch.h).
  /// The 3D repeater follows it too, for its fallback.
  double mean_error_px = 0.0;
  int lost = 0;                         ///< tracked features lost in this frame
  int recovered = 0;                    ///< lost features recovered in this frame (3D)
  std::int64_t features_lost = 0;       ///< cumulative since the repeat began
  std::int64_t features_recovered = 0;  ///< cumulative since the repeat began

  // 3D only.
  bool pose_valid = false;  ///< the pose below was estimated in this frame
  /// Current camera in the active milestone's first camera frame (metric).
  Eigen::Isometry3d T_first_cam = Eigen::Isometry3d::Identity();
  bool essential_used = false;  ///< the essential matrix gave this frame's initial pose
  int essential_inliers = 0;
  /// Scale ratio (ScaleRatio) that made the essential matrix's translation metric.
  double scale_ratio = 0.0;
  double reprojection_rms_px = 0.0;  ///< of the tracked features after pose refinement
  double lateral_offset_m = 0.0;     ///< PathOffset::lateral_m (> 0: left of the route)
  /// PathOffset::heading_rad (> 0: turned left); 2D: the progress fit's common offset
  /// c / fx (EstimateMilestoneProgress), the heading error plus mean parallax [rad].
  double heading_error_rad = 0.0;
  /// PathOffset::progress in the active milestone; 2D: the progress fit's p.
  double progress = 0.0;
  bool fallback_2d = false;  ///< steered by the funnel-lane vote (no 3-D pose)
};

/// A repeat of a taught route. Stateful; not copyable.
class Repeater {
 public:
  Repeater() = default;
  Repeater(const Repeater&) = delete;
  Repeater& operator=(const Repeater&) = delete;
  virtual ~Repeater() = default;

  /// One camera frame: a CV_8UC1 image of the map's camera size taken at t_s [s] (finite,
  /// not decreasing). Throws std::invalid_argument otherwise. Once the status is not
  /// kDriving it stays so and the command is zero.
  virtual RepeatCommand Update(const cv::Mat& gray, double t_s) = 0;
  /// The forward speed the robot actually drove after the last Update, when something
  /// above the repeater changed its command (a supervisor holding the robot: 0). The 2D
  /// repeater's distance bound counts the distance driven from it. Default: ignored.
  virtual void SetExecutedSpeed(double /*v_mps*/) {}
  /// "2d" or "3d".
  virtual const char* method() const = 0;
  virtual const TeachMap& map() const = 0;
};

}  // namespace trackbed::teach_repeat
