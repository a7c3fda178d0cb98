// Repeat 2D: the funnel-lane repeater's options, milestone switching and steering (see
// funnel_lane_controller.h).
#include "trackbed/teach_repeat/funnel_lane_controller.h"

#include <cmath>
#include <string>
#include <utility>

#include "teach_repeat_tracks.h"
#include "trackbed/common/option_error.h"
#include "trackbed/teach_repeat/funnel_lane_vote.h"

namespace trackbed::teach_repeat {
namespace {

/// The base's settings from validated options (the options are checked before the map).
MilestoneRepeaterSettings SettingsOf(const FunnelLaneOptions& options) {
  options.Validate();
  MilestoneRepeaterSettings s;
  s.name = "FunnelLaneRepeater";
  s.start_milestone = options.start_milestone;
  s.tracker = options.tracker;
  s.switch_hysteresis_px = options.switch_hysteresis_px;
  s.switch_error = options.switch_error;
  s.remove_rotation = options.remove_rotation;
  s.min_features = options.min_features;
  s.lost_patience_frames = options.lost_patience_frames;
  s.forward_speed_mps = options.forward_speed_mps;
  return s;
}

}  // namespace

void FunnelLaneOptions::Validate() const {
  option_check::Positive("forward_speed_mps", forward_speed_mps);
  option_check::Positive("turn_rate_radps", turn_rate_radps);
  if (!(min_net_vote >= 0.0 && min_net_vote < 1.0)) {
    throw OptionError("min_net_vote",
                      "must be in [0, 1) (got " + option_check::Describe(min_net_vote) + ")");
  }
  option_check::NonNegative("switch_hysteresis_px", switch_hysteresis_px);
  option_check::OffOrAtLeast("max_milestone_overrun", max_milestone_overrun, 1.0);
  option_check::AtLeast("min_frames_per_milestone", min_frames_per_milestone, 1);
  option_check::AtLeast("min_features", min_features, 1);
  option_check::AtLeast("lost_patience_frames", lost_patience_frames, 1);
  option_check::AtLeast("start_milestone", start_milestone, 0);
  if (!(switch_progress > 0.0 && switch_progress <= 2.0)) {
    throw OptionError("switch_progress",
                      "must be in (0, 2] (got " + option_check::Describe(switch_progress) + ")");
  }
  option_check::NonNegative("heading_deadband_px", heading_deadband_px);
  option_check::Nested("progress", progress);
  option_check::Nested("tracker", tracker);
}

FunnelLaneRepeater::FunnelLaneRepeater(TeachMap map, const FunnelLaneOptions& options)
    : MilestoneRepeater(std::move(map), SettingsOf(options)), options_(options) {}

void FunnelLaneRepeater::MilestoneStarted(const Milestone& m) {
  // Whether the images can tell where the robot is in this milestone at all: the fit
  // of its own destination positions.
  std::vector<cv::Point2f> last;
  for (const MilestoneFeature& f : m.features) last.push_back(f.last_px);
  taught_flow_measurable_ =
      EstimateMilestoneProgress(map_.camera, m, last, std::vector<bool>(last.size(), true),
                                options_.progress)
          .valid;
}

void FunnelLaneRepeater::RepeatFrame(const cv::Mat& /*gray*/, RepeatCommand* cmd) {
  cmd->lost = tracks_->CommitLosses();  // the 2D method has no way to find them again
  lost_total_ += cmd->lost;

  const Milestone* m = &map_.milestones[static_cast<std::size_t>(milestone_)];
  detail::FunnelFrame frame =
      detail::EvaluateFunnel(map_.camera, *m, tracks_->tracks(), options_.remove_rotation);
  // The error minimum is followed every frame, so that it is ready when the progress
  // cannot be measured.
  const bool passed_minimum = switch_->Update(frame);
  MilestoneProgress progress =
      detail::ProgressOf(map_.camera, *m, tracks_->tracks(), options_.progress);
  bool passed_progress = passed_minimum;
  if (options_.switch_by_progress) {
    // A milestone without measurable taught flow (a few images cut short by too few
    // features, or a turn in place) is, as far as its images tell, reached at its key
    // image: its error has no minimum to wait for.
    passed_progress =
        !taught_flow_measurable_ ||
        (progress.valid ? progress.progress >= options_.switch_progress : passed_minimum);
  }
  // The distance bound (file comment): driven past the milestone by the command alone.
  const bool overran = options_.max_milestone_overrun > 0.0 && taught_flow_measurable_ &&
                       DrivenInMilestone() > options_.max_milestone_overrun * m->baseline_m;
  const bool passed =
      (passed_progress || overran) && frames_in_milestone_ > options_.min_frames_per_milestone;
  cmd->mean_error_px = switch_->error_px();
  if (passed) {
    if (milestone_ + 1 >= static_cast<int>(map_.milestones.size())) {
      Finish(cmd);
      return;
    }
    const Milestone& next = map_.milestones[static_cast<std::size_t>(milestone_ + 1)];
    const std::vector<cv::Point2f> guesses = detail::ShiftedGuesses(*m, tracks_->tracks(), next);
    StartMilestone(milestone_ + 1, guesses);
    cmd->switched = true;
    cmd->switched_by_distance = !passed_progress;
    m = &next;
    frame = detail::EvaluateFunnel(map_.camera, *m, tracks_->tracks(), options_.remove_rotation);
    switch_->Update(frame);
    cmd->mean_error_px = switch_->error_px();
    progress = detail::ProgressOf(map_.camera, *m, tracks_->tracks(), options_.progress);
  }
  if (progress.valid) {
    cmd->progress = progress.progress;
    cmd->heading_error_rad = progress.heading_px / map_.camera.fx;  // > 0: turned left
  }

  cmd->milestone = milestone_;
  cmd->features = static_cast<int>(tracks_->size());
  cmd->tracked = tracks_->tracked();
  cmd->votes_left = frame.tally.left;
  cmd->votes_right = frame.tally.right;
  cmd->votes_straight = frame.tally.straight;
  cmd->features_lost = lost_total_;
  if (GoStraightIfTooFewFeatures(cmd)) return;
  cmd->decision = DecideTurn(frame.tally, options_.min_net_vote);
  if (cmd->decision == TurnVote::kStraight && options_.heading_correction && progress.valid &&
      std::abs(progress.heading_px) > options_.heading_deadband_px) {
    cmd->decision = progress.heading_px > 0.0 ? TurnVote::kRight : TurnVote::kLeft;
  }
  cmd->twist.v_mps = options_.forward_speed_mps;
  cmd->twist.yaw_rate_radps =
      static_cast<double>(static_cast<int>(cmd->decision)) * options_.turn_rate_radps;
}

}  // namespace trackbed::teach_repeat
