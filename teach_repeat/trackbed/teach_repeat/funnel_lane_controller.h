// Repeat 2D: qualitative, funnel-lane path following (Chen & Birchfield 2006, as Choi &
// Ha 2011 §II state it; docs/teach_repeat.md). This file has the repeater and this
// comment the method; the rules and the vote are in funnel_lane_vote.h, the milestone
// switch and the progress fit in milestone_switch.h (the 3D repeater falls back on
// both), the tracking every frame starts with in milestone_repeater.h.
//
// For feature i, f_c is its x in the current image and f_d its x in the milestone's
// destination (last) image, both relative to the principal point (> 0 right of it). The
// rules (Choi & Ha eq. 1):
//   turn right  if f_c > 0 and f_d < 0,  or  f_c > 0 and f_c > f_d;
//   turn left   if f_c < 0 and f_d > 0,  or  f_c < 0 and f_c < f_d;
//   otherwise go straight.
// Approaching the destination, a feature moves away from the image centre toward f_d;
// as long as it lies between the centre and f_d (inside its "funnel lane") the robot may
// go straight; outside, turning toward it brings it back.
//
// Our readings, where the paper leaves the details open:
//
// * Matching. Features are not matched by descriptors: each milestone's features are
//   tracked by KLT, as the paper does in teaching. When a milestone becomes active its
//   features are tracked from its key image (stored in the map) into the current image;
//   from then on from the previous repeat image into the current one. A feature that KLT
//   loses stays lost for the rest of the milestone (the 2D method has no way to find it
//   again — Choi & Ha's experiment 1); the next milestone brings fresh features.
// * The vote. Bang-bang: with N_R, N_L, N_S votes, turn right at the full turn rate when
//   (N_R − N_L) > min_net_vote · (N_R + N_L + N_S), left when (N_L − N_R) exceeds it,
//   else straight. min_net_vote = 0 is the bare majority of the turn votes; a small
//   positive value keeps a few noisy features from steering.
// * The switch. "The mean x-error stops decreasing and starts to increase." Two readings
//   of "mean x-error", an option (`switch_error`):
//     - kMeanAbsolute, the literal one: E = mean_i |e_i|, e_i = f_c − f_d;
//     - kMeanOutward (default): E = |mean_i sign(f_d)·e_i|, the mean of the errors
//       counted outward from the image centre (negative while a feature has not yet
//       reached its destination, positive once it has passed it: features move outward
//       as the robot approaches), which crosses zero at the destination.
//   Why the second: off the taught path by y, features on the near side of the route
//   appear as if the robot were behind the destination and those on the far side as if
//   it were ahead, both by ~fx·y/Z — pixels to tens of pixels, more than the
//   approach moves them in a frame. |e_i| summed over both sides then has a flat
//   minimum spread over the whole stretch between the two sides' crossings, and the
//   switch comes late (by tens of centimetres in our tests, with y = 0.2 m); in the
//   outward mean the two sides' offsets cancel to first order.
//   With `remove_rotation` (default) errors are bearing errors, e_i = fx·(atan(f_c/fx) −
//   atan(f_d/fx)), minus their common part: a pure yaw of the robot shifts every bearing
//   by the same angle, and the bang-bang turns, which move every feature at once, would
//   otherwise look like approach or retreat.
//   E and the common part are followed through their frame-to-frame changes over the
//   features tracked in both frames, accumulated from their values when the milestone
//   became active: features lost on the way (to an occluder on one side, say) move
//   neither. The milestone is passed when E has risen more than `switch_hysteresis_px`
//   above its minimum since then (ErrorMinimumDetector), and no earlier than
//   `min_frames_per_milestone` frames after it began.
// * Progress (ours, default). Both readings of the error fail in curves: there the
//   features often lie on one side of the image (the inside of the curve passes out of
//   view), where the outward mean minus the common part is zero whatever the robot's
//   position, and a heading error moves the flat minimum of either by tens of
//   centimetres. So the robot's place within the milestone is measured instead, as a
//   fraction of the taught image flow (EstimateMilestoneProgress): each feature moved
//   by F_i = its last minus its first position while the teach camera went from the key
//   image to the destination; now it has moved by D_i from its first position. Fitted
//   over all features, D_i = p·F_i + (c, b): the progress p (0 at the key image, 1 at
//   the destination) and a common offset, c in x (a yaw from the taught heading at that
//   place, and the lateral offset's mean parallax), b in y (pitch). Positions are
//   cylindrical (azimuth and elevation, in pixels at the centre), so that a yaw shifts
//   x alike everywhere and leaves y alone; y carries the approach alone, x the approach
//   and the turns of the teach. The milestone is passed when p reaches
//   `switch_progress`; when the flow of the tracked features is too small to measure p
//   the error minimum decides, and a milestone whose own taught flow is too small (a
//   few images cut short by too few features, a turn in place) is passed after
//   `min_frames_per_milestone` frames: its images cannot tell where in it the robot is,
//   and its error has no minimum to wait for.
// * Heading (ours, default). The funnel-lane rules only see a feature leave its lane on
//   its own side: a robot turned away from the inside of a curve whose features are all
//   on the outside sees every feature between the centre and its destination, votes
//   "straight", and falls behind the taught heading until the features are lost. When
//   the vote says straight but the common offset c of the progress fit exceeds
//   `heading_deadband_px`, the robot turns toward the taught heading at that place
//   (c > 0: features right of where the teach saw them, the robot turned left: right).
// * Distance bound (ours, default). The images can lose the place within a milestone
//   while still steering: on low-texture ground seen mostly far away the progress fit
//   wanders (back below 0 while the robot drives on) and the error has no clear minimum,
//   so the robot keeps the milestone for metres; in a curve it then steers to a heading
//   taught metres behind and drifts to the outside (4 m behind and 1.1 m outside after
//   40 m of sandy loam: docs/results/2026-12-06-long-routes.md). Bearing-only
//   navigation takes the distance along the path from odometry (Krajník et al. 2010,
//   "Simple yet stable bearing-only navigation", J. Field Robotics 27(5)); here it only
//   bounds the images: a milestone whose taught flow is measurable is passed once the
//   repeat has driven `max_milestone_overrun` times its taught baseline in it, counted
//   from the commands' forward speed as executed (Repeater::SetExecutedSpeed: a robot
//   held still drives nothing; wheel slip makes the bound later, never earlier).
// * Starting a milestone. The first milestone's features are tracked from its key image
//   starting at their key-image positions moved by the global image shift (phase
//   correlation, EstimateImageShift); a later milestone's, moved by the median
//   displacement of the previous milestone's features. Features the first KLT pass
//   misses get a second pass from guesses corrected by the median of those found.
#pragma once

#include <cmath>

#include <opencv2/core.hpp>

#include "trackbed/common/units.h"
#include "trackbed/perception/feature_tracker.h"
#include "trackbed/teach_repeat/milestone_repeater.h"
#include "trackbed/teach_repeat/milestone_switch.h"
#include "trackbed/teach_repeat/teach_map.h"
#include "trackbed/teach_repeat/teach_repeat.h"

namespace trackbed::teach_repeat {

/// Options of FunnelLaneRepeater.
struct FunnelLaneOptions {
  /// Constant forward speed [m/s], > 0 (Choi & Ha's lab repeat: 0.05 m/s). Not a key of
  /// this struct: a run sets it from `teach_repeat.repeat_speed_mps`, which both
  /// repeaters share.
  double forward_speed_mps = 0.05;
  /// Bang-bang turn rate [rad/s], > 0 (Choi & Ha's lab repeat: 4°/s). Not a key of this
  /// struct: a run sets it from `teach_repeat.repeat_turn_rate_deg_s`.
  double turn_rate_radps = units::Radians(4.0);
  /// Net vote fraction needed to turn, in [0, 1) (see the file comment).
  double min_net_vote = 0.1;
  /// Rise of the accumulated x-error above its minimum that switches milestones [px], >= 0.
  double switch_hysteresis_px = 1.0;
  /// The error the milestone switch follows when the progress is not used or not
  /// measurable (file comment).
  SwitchError switch_error = SwitchError::kMeanOutward;
  /// Switch by the measured progress when it is measurable (file comment, "Progress").
  bool switch_by_progress = true;
  /// Progress that passes a milestone (1 = its destination image), in (0, 2].
  double switch_progress = 1.0;
  /// Turn toward the taught heading when the vote says straight (file comment).
  bool heading_correction = true;
  /// |c| beyond which the heading correction turns [bearing px], >= 0 (fx = 381 px:
  /// 5 px is 0.75°).
  double heading_deadband_px = 5.0;
  /// The progress fit.
  MilestoneProgressOptions progress;
  /// Remove the common rotation from the x-errors before switching (file comment).
  bool remove_rotation = true;
  /// Distance bound (file comment, "Distance bound"): a milestone is passed at the latest
  /// once the repeat has driven this many times its taught baseline in it (its commands'
  /// forward speed as executed); 0 turns the bound off, else >= 1. Its key is
  /// `teach_repeat.max_milestone_overrun`, beside the section of this struct's others.
  double max_milestone_overrun = 2.0;
  /// Frames a milestone stays active at least before it may be switched, >= 1.
  int min_frames_per_milestone = 3;
  /// Fewer tracked features than this is "too few": the robot goes straight, >= 1.
  int min_features = 8;
  /// Consecutive frames with too few features before the repeat is lost, >= 1.
  int lost_patience_frames = 20;
  /// Milestone the repeat starts at (the robot stands near its key image), >= 0.
  int start_milestone = 0;
  /// KLT tracking of the milestone features (`tracker.*`, perception/feature_tracker.h).
  perception::FeatureTrackerOptions tracker = DefaultRepeatTrackerOptions();

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `teach_repeat.funnel_lane`), read and written by the config archive
  /// (trackbed/common/archive.h); the speeds and max_milestone_overrun are keys
  /// elsewhere (above).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("min_net_vote", &min_net_vote);
    a->Visit("switch_hysteresis_px", &switch_hysteresis_px);
    a->VisitEnum("switch_error", &switch_error,
                 {{"mean_absolute", SwitchError::kMeanAbsolute},
                  {"mean_outward", SwitchError::kMeanOutward}});
    a->Visit("switch_by_progress", &switch_by_progress);
    a->Visit("switch_progress", &switch_progress);
    a->Visit("heading_correction", &heading_correction);
    a->Visit("heading_deadband_px", &heading_deadband_px);
    a->Visit("progress", &progress);
    a->Visit("remove_rotation", &remove_rotation);
    a->Visit("min_frames_per_milestone", &min_frames_per_milestone);
    a->Visit("min_features", &min_features);
    a->Visit("lost_patience_frames", &lost_patience_frames);
    a->Visit("start_milestone", &start_milestone);
    a->Visit("tracker", &tracker);
  }
};

/// The 2D repeat (see the file comment). Stateful; not copyable.
class FunnelLaneRepeater : public MilestoneRepeater {
 public:
  /// Throws OptionError for invalid options, std::invalid_argument for a map without
  /// milestones or a start milestone beyond it.
  FunnelLaneRepeater(TeachMap map, const FunnelLaneOptions& options = {});

  const char* method() const override { return "2d"; }
  const FunnelLaneOptions& options() const { return options_; }

 private:
  void RepeatFrame(const cv::Mat& gray, RepeatCommand* cmd) override;
  void MilestoneStarted(const Milestone& m) override;

  FunnelLaneOptions options_;
  bool taught_flow_measurable_ = true;  // the active milestone's own flow gives a progress
};

}  // namespace trackbed::teach_repeat
