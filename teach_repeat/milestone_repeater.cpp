// The common part of the two repeaters (see milestone_repeater.h).
#include "trackbed/teach_repeat/milestone_repeater.h"
#include "trackbed/perception/opencv_views.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "teach_repeat_tracks.h"

namespace trackbed::teach_repeat {

perception::FeatureTrackerOptions DefaultRepeatTrackerOptions() {
  perception::FeatureTrackerOptions o;
  o.window_px = 21;
  o.pyramid_levels = 4;
  return o;
}

MilestoneRepeater::MilestoneRepeater(TeachMap map, const MilestoneRepeaterSettings& settings)
    : map_(std::move(map)), settings_(settings) {
  const std::string name = settings_.name;
  if (map_.milestones.empty()) {
    throw std::invalid_argument(name + ": the teach map has no milestones");
  }
  if (settings_.start_milestone >= static_cast<int>(map_.milestones.size())) {
    throw std::invalid_argument(name + ": start_milestone " +
                                std::to_string(settings_.start_milestone) + " beyond the map's " +
                                std::to_string(map_.milestones.size()) + " milestones");
  }
  tracks_ = std::make_unique<detail::MilestoneTracks>(settings_.tracker);
  switch_ = std::make_unique<detail::MilestoneSwitch>(
      settings_.switch_hysteresis_px, settings_.switch_error, settings_.remove_rotation);
}

MilestoneRepeater::~MilestoneRepeater() = default;

void MilestoneRepeater::CheckInput(const cv::Mat& gray, double t_s) const {
  if (gray.empty() || gray.type() != CV_8UC1 ||
      gray.size() != perception::CvImageSize(map_.camera)) {
    throw std::invalid_argument(
        std::string(settings_.name) + "::Update: needs a CV_8UC1 image of " +
        std::to_string(map_.camera.width_px) + "x" + std::to_string(map_.camera.height_px) + " px");
  }
  if (!std::isfinite(t_s) || (started_ && t_s < last_t_s_)) {
    throw std::invalid_argument(std::string(settings_.name) +
                                "::Update: time must be finite and not decreasing");
  }
}

RepeatCommand MilestoneRepeater::Update(const cv::Mat& gray, double t_s) {
  CheckInput(gray, t_s);
  if (started_) driven_in_milestone_m_ += executed_v_mps_ * (t_s - last_t_s_);
  last_t_s_ = t_s;
  RepeatCommand cmd;
  cmd.milestone = milestone_;
  cmd.features_lost = lost_total_;
  cmd.features_recovered = recovered_total_;
  if (status_ != RepeatStatus::kDriving) {
    cmd.status = status_;
    return cmd;
  }

  tracks_->BuildPyramid(gray, &curr_pyramid_);
  if (!started_) {
    const int start = settings_.start_milestone;
    HoldMilestones(start);
    StartMilestone(start,
                   detail::StartGuesses(map_.milestones[static_cast<std::size_t>(start)], gray));
    started_ = true;
  } else {
    tracks_->Advance(prev_pyramid_, curr_pyramid_);
  }
  ++frames_in_milestone_;
  RepeatFrame(gray, &cmd);
  std::swap(prev_pyramid_, curr_pyramid_);
  executed_v_mps_ = cmd.twist.v_mps;
  return cmd;
}

void MilestoneRepeater::StartMilestone(int index, const std::vector<cv::Point2f>& guesses) {
  milestone_ = index;
  HoldMilestones(index);
  const Milestone& m = map_.milestones[static_cast<std::size_t>(index)];
  tracks_->Start(m, curr_pyramid_, guesses);
  switch_->Reset();
  frames_in_milestone_ = 0;
  driven_in_milestone_m_ = 0.0;
  MilestoneStarted(m);
}

void MilestoneRepeater::HoldMilestones(int index) {
  const int first = index;
  const int last = std::min(index + 1, static_cast<int>(map_.milestones.size()) - 1);
  for (int k = held_first_; k <= held_last_; ++k) {
    if (k >= first && k <= last) continue;
    ReleaseKeyImage(&map_.milestones[static_cast<std::size_t>(k)]);
    ReleaseFeatures(&map_.milestones[static_cast<std::size_t>(k)]);
  }
  for (int k = first; k <= last; ++k) {
    LoadKeyImage(map_.camera, &map_.milestones[static_cast<std::size_t>(k)]);
    LoadFeatures(&map_.milestones[static_cast<std::size_t>(k)]);
  }
  held_first_ = first;
  held_last_ = last;
}

void MilestoneRepeater::Finish(RepeatCommand* cmd) {
  status_ = RepeatStatus::kFinished;
  cmd->status = status_;
  cmd->features_lost = lost_total_;
  cmd->features_recovered = recovered_total_;
}

bool MilestoneRepeater::GoStraightIfTooFewFeatures(RepeatCommand* cmd) {
  if (cmd->tracked >= settings_.min_features) {
    too_few_frames_ = 0;
    return false;
  }
  cmd->too_few_features = true;
  if (++too_few_frames_ > settings_.lost_patience_frames) {
    status_ = RepeatStatus::kLost;
    cmd->status = status_;
    cmd->twist = {};
  } else {
    cmd->twist.v_mps = settings_.forward_speed_mps;
  }
  return true;
}

}  // namespace trackbed::teach_repeat
