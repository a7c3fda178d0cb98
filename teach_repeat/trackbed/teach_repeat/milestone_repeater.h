// What the 2D and the 3D repeater share (funnel_lane_controller.h,
// milestone_localizer_3d.h): the active milestone's feature tracks, the 2D milestone
// switch (the 2D repeater's switch, the 3D one's fallback), the repeat's status and
// counters, and the beginning of every frame, so that each repeater states only how it
// switches milestones and steers.
//
// Every frame (MilestoneRepeater::Update), before the repeater's own part (RepeatFrame):
//   - the input is checked: a CV_8UC1 image of the map's camera size, a time that is
//     finite and not decreasing;
//   - a repeat that has finished or is lost returns its status and a zero command;
//   - the image's tracking pyramid is built and the active milestone's features are
//     tracked into it by KLT from the previous image; on the first frame the start
//     milestone begins instead: its features are tracked from its key image, starting at
//     their key-image positions moved by the global image shift (phase correlation).
// After it this image's pyramid becomes the previous one.
//
// A map whose key images are held in their files (teach_map.h) is read as the repeat
// goes: when a milestone becomes active its key image and the next one's are read, and
// the key images behind are dropped, so memory and per-frame cost do not grow with the
// route.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "trackbed/perception/feature_tracker.h"
#include "trackbed/teach_repeat/milestone_switch.h"
#include "trackbed/teach_repeat/teach_map.h"
#include "trackbed/teach_repeat/teach_repeat.h"

namespace trackbed::teach_repeat {

namespace detail {
class MilestoneTracks;
}  // namespace detail

/// Repeat tracking options for milestone features: OpenCV's 21 px window and 4 pyramid
/// levels, so that the start of a milestone (KLT from its key image) catches features
/// displaced by up to ~80 px (a repeat that starts 0.2 m and 5° off).
perception::FeatureTrackerOptions DefaultRepeatTrackerOptions();

/// What MilestoneRepeater takes from a repeater's (validated) options.
struct MilestoneRepeaterSettings {
  /// The repeater's class name, which begins its error messages.
  const char* name = "";
  /// Milestone the repeat starts at, >= 0.
  int start_milestone = 0;
  /// KLT tracking of the milestone features.
  perception::FeatureTrackerOptions tracker;
  /// The 2D milestone switch (milestone_switch.h).
  double switch_hysteresis_px = 1.0;
  SwitchError switch_error = SwitchError::kMeanOutward;
  bool remove_rotation = true;
  /// Fewer tracked features than this is "too few": the robot goes straight, >= 1.
  int min_features = 8;
  /// Consecutive frames with too few features before the repeat is lost, >= 1.
  int lost_patience_frames = 20;
  /// Constant forward speed [m/s], > 0.
  double forward_speed_mps = 0.05;
};

/// The base of the two repeaters (see the file comment). Stateful; not copyable.
class MilestoneRepeater : public Repeater {
 public:
  ~MilestoneRepeater() override;

  /// The common beginning of the frame (file comment), then RepeatFrame. Throws
  /// std::invalid_argument, naming the repeater, for an image or time it cannot take.
  RepeatCommand Update(const cv::Mat& gray, double t_s) final;
  const TeachMap& map() const final { return map_; }
  void SetExecutedSpeed(double v_mps) final { executed_v_mps_ = v_mps; }

 protected:
  /// Throws std::invalid_argument, naming settings.name, for a map without milestones or
  /// a start milestone beyond it. `settings` must be valid.
  MilestoneRepeater(TeachMap map, const MilestoneRepeaterSettings& settings);

  /// The repeater's own part of a frame while driving, once the active milestone's
  /// features are tracked into `gray`: switches milestones, steers and fills `cmd` (which
  /// holds the milestone and the cumulative counters of the frame's start).
  virtual void RepeatFrame(const cv::Mat& gray, RepeatCommand* cmd) = 0;
  /// What a repeater keeps per milestone, set up when `m` has become the active one.
  virtual void MilestoneStarted(const Milestone& m) = 0;

  /// Makes milestone `index` active: its features are tracked by KLT from its key image
  /// into the current image, starting at `guesses` (one per feature); the 2D switch and
  /// the frame count start over; then MilestoneStarted.
  void StartMilestone(int index, const std::vector<cv::Point2f>& guesses);
  /// Distance driven since the active milestone became active [m]: the forward speed
  /// of each command as executed (SetExecutedSpeed) times the time to the next frame.
  double DrivenInMilestone() const { return driven_in_milestone_m_; }
  /// Ends the repeat (the last milestone was passed): status kFinished, with the
  /// cumulative counters.
  void Finish(RepeatCommand* cmd);
  /// Whether this frame has too few tracked features (cmd->tracked < min_features); the
  /// command then goes straight on at the forward speed, hoping to see again — or, after
  /// more than lost_patience_frames such frames in a row, the repeat is lost: status
  /// kLost and a zero command.
  bool GoStraightIfTooFewFeatures(RepeatCommand* cmd);

  TeachMap map_;
  std::unique_ptr<detail::MilestoneTracks> tracks_;
  std::unique_ptr<detail::MilestoneSwitch> switch_;
  int milestone_ = 0;                 ///< the active milestone
  int frames_in_milestone_ = 0;       ///< frames since it became active, this one included
  std::int64_t lost_total_ = 0;       ///< features lost since the repeat began
  std::int64_t recovered_total_ = 0;  ///< features recovered since the repeat began (3D)

 private:
  /// Throws std::invalid_argument unless `gray` is a CV_8UC1 image of the map's camera
  /// size and `t_s` is finite and, once started, not before the last frame's time.
  void CheckInput(const cv::Mat& gray, double t_s) const;
  /// Holds the key images and features of milestones index … index + 1 in memory and
  /// drops those held before that are not among them (only those that have files).
  void HoldMilestones(int index);

  MilestoneRepeaterSettings settings_;
  perception::TrackingPyramid prev_pyramid_, curr_pyramid_;
  bool started_ = false;
  double last_t_s_ = 0.0;
  double executed_v_mps_ = 0.0;         ///< the last command's forward speed, as executed
  double driven_in_milestone_m_ = 0.0;  ///< see DrivenInMilestone
  int too_few_frames_ = 0;
  int held_first_ = 0, held_last_ = -1;  ///< the milestones whose key images and features are held
  RepeatStatus status_ = RepeatStatus::kDriving;
};

}  // namespace trackbed::teach_repeat
