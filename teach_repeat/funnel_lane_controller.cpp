// Repeat 2D: funnel-lane rules, the vote and milestone switching (see
// funnel_lane_controller.h).
#include "trackbed/teach_repeat/funnel_lane_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "teach_repeat_tracks.h"
#include "trackbed/common/option_error.h"
#include "trackbed/teach_repeat/teach_repeat_geometry.h"

namespace trackbed::teach_repeat {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void AtLeast(const char* field, int value, int minimum) {
  if (value < minimum) {
    throw OptionError(
        field, "must be >= " + std::to_string(minimum) + " (got " + std::to_string(value) + ")");
  }
}

}  // namespace

TurnVote FunnelLaneVote(double f_current_px, double f_destination_px) {
  const double fc = f_current_px, fd = f_destination_px;
  // Choi & Ha 2011, eq. (1).
  if ((fc > 0.0 && fd < 0.0) || (fc > 0.0 && fc > fd)) return TurnVote::kRight;
  if ((fc < 0.0 && fd > 0.0) || (fc < 0.0 && fc < fd)) return TurnVote::kLeft;
  return TurnVote::kStraight;
}

TurnVote DecideTurn(const VoteTally& tally, double min_net_vote) {
  const int total = tally.total();
  if (total == 0) return TurnVote::kStraight;
  const double needed = min_net_vote * total;
  if (tally.right - tally.left > needed) return TurnVote::kRight;
  if (tally.left - tally.right > needed) return TurnVote::kLeft;
  return TurnVote::kStraight;
}

ErrorMinimumDetector::ErrorMinimumDetector(double hysteresis) : hysteresis_(hysteresis) {
  if (!(hysteresis >= 0.0 && std::isfinite(hysteresis))) {
    throw std::invalid_argument("ErrorMinimumDetector: hysteresis must be finite and >= 0");
  }
  Reset();
}

void ErrorMinimumDetector::Reset() {
  minimum_ = std::numeric_limits<double>::infinity();
  passed_ = false;
}

bool ErrorMinimumDetector::Update(double error) {
  if (passed_) return true;
  if (!std::isfinite(error)) return false;
  minimum_ = std::min(minimum_, error);
  passed_ = error > minimum_ + hysteresis_;
  return passed_;
}

void MilestoneProgressOptions::Validate() const {
  option_check::Positive("min_flow_spread_px", min_flow_spread_px);
  option_check::Positive("outlier_px", outlier_px);
  AtLeast("min_features", min_features, 3);
}

namespace {

/// One feature's taught flow F and current displacement D, x in bearing pixels.
struct FlowSample {
  double fx, fy, dx, dy;
};

/// Least squares of D = p·F + (c, b) over `samples` with weights `use` (file comment):
/// the offsets eliminated, p = Σ(F − F̄)·(D − D̄) / Σ|F − F̄|².
bool FitProgress(const std::vector<FlowSample>& samples, const std::vector<bool>& use,
                 double min_spread_px, MilestoneProgress* out) {
  double n = 0.0, mfx = 0.0, mfy = 0.0, mdx = 0.0, mdy = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!use[i]) continue;
    const FlowSample& s = samples[i];
    n += 1.0;
    mfx += s.fx;
    mfy += s.fy;
    mdx += s.dx;
    mdy += s.dy;
  }
  if (n < 3.0) return false;
  mfx /= n;
  mfy /= n;
  mdx /= n;
  mdy /= n;
  double sff = 0.0, sfd = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!use[i]) continue;
    const FlowSample& s = samples[i];
    sff += (s.fx - mfx) * (s.fx - mfx) + (s.fy - mfy) * (s.fy - mfy);
    sfd += (s.fx - mfx) * (s.dx - mdx) + (s.fy - mfy) * (s.dy - mdy);
  }
  if (!(std::sqrt(sff / n) >= min_spread_px)) return false;
  out->progress = sfd / sff;
  out->heading_px = mdx - out->progress * mfx;
  out->pitch_px = mdy - out->progress * mfy;
  out->features = static_cast<int>(n);
  return true;
}

double Residual(const FlowSample& s, const MilestoneProgress& p) {
  return std::hypot(s.dx - p.progress * s.fx - p.heading_px, s.dy - p.progress * s.fy - p.pitch_px);
}

}  // namespace

MilestoneProgress EstimateMilestoneProgress(const CameraIntrinsics& camera, const Milestone& m,
                                            const std::vector<cv::Point2f>& current_px,
                                            const std::vector<bool>& tracked,
                                            const MilestoneProgressOptions& options) {
  if (current_px.size() != m.features.size() || tracked.size() != m.features.size()) {
    throw std::invalid_argument(
        "EstimateMilestoneProgress: one current position and flag per milestone feature");
  }
  // Cylindrical coordinates in pixels at the centre: azimuth fx·atan(x/fx), which a yaw
  // shifts alike everywhere, and fy·tan(elevation), which a yaw leaves alone (the image
  // y of a point off the centre changes with a yaw, by ~y·x·yaw/fx: with features on one
  // side that would read as progress).
  const auto cylinder = [&camera](const cv::Point2f& q) {
    const double x = (static_cast<double>(q.x) - camera.cx) / camera.fx;
    const double y = static_cast<double>(q.y) - camera.cy;
    return cv::Point2d(camera.fx * std::atan(x), y / std::sqrt(1.0 + x * x));
  };
  std::vector<FlowSample> samples;
  samples.reserve(m.features.size());
  for (std::size_t i = 0; i < m.features.size(); ++i) {
    if (!tracked[i]) continue;
    const MilestoneFeature& f = m.features[i];
    const cv::Point2d a = cylinder(f.first_px), b = cylinder(f.last_px),
                      c = cylinder(current_px[i]);
    samples.push_back({b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y});
  }
  MilestoneProgress result;
  if (static_cast<int>(samples.size()) < options.min_features) return result;
  std::vector<bool> use(samples.size(), true);
  MilestoneProgress first;
  if (!FitProgress(samples, use, options.min_flow_spread_px, &first)) return result;
  // Second fit without the features far from the first (a KLT track slid onto an
  // occluder, a feature on a moving object).
  std::vector<double> residuals;
  for (const FlowSample& s : samples) residuals.push_back(Residual(s, first));
  std::vector<double> sorted = residuals;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double bound = std::max(options.outlier_px, 3.0 * sorted[sorted.size() / 2]);
  for (std::size_t i = 0; i < samples.size(); ++i) use[i] = residuals[i] <= bound;
  MilestoneProgress second;
  if (!FitProgress(samples, use, options.min_flow_spread_px, &second) ||
      second.features < options.min_features) {
    return result;
  }
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (use[i]) sum_sq += Residual(samples[i], second) * Residual(samples[i], second);
  }
  second.rms_px = std::sqrt(sum_sq / second.features);
  second.valid = true;
  return second;
}

perception::FeatureTrackerOptions DefaultRepeatTrackerOptions() {
  perception::FeatureTrackerOptions o;
  o.window_px = 21;
  o.pyramid_levels = 4;
  return o;
}

void FunnelLaneOptions::Validate() const {
  option_check::Positive("forward_speed_mps", forward_speed_mps);
  option_check::Positive("turn_rate_radps", turn_rate_radps);
  if (!(min_net_vote >= 0.0 && min_net_vote < 1.0)) {
    throw OptionError("min_net_vote",
                      "must be in [0, 1) (got " + option_check::Describe(min_net_vote) + ")");
  }
  option_check::NonNegative("switch_hysteresis_px", switch_hysteresis_px);
  AtLeast("min_frames_per_milestone", min_frames_per_milestone, 1);
  AtLeast("min_features", min_features, 1);
  AtLeast("lost_patience_frames", lost_patience_frames, 1);
  AtLeast("start_milestone", start_milestone, 0);
  if (!(switch_progress > 0.0 && switch_progress <= 2.0)) {
    throw OptionError("switch_progress",
                      "must be in (0, 2] (got " + option_check::Describe(switch_progress) + ")");
  }
  option_check::NonNegative("heading_deadband_px", heading_deadband_px);
  option_check::Nested("progress", progress);
  option_check::Nested("tracker", tracker);
}

namespace detail {

FunnelFrame EvaluateFunnel(const CameraIntrinsics& camera, const Milestone& m,
                           const std::vector<FeatureTrack>& tracks, bool bearing) {
  FunnelFrame f;
  f.error_px.assign(tracks.size(), kNaN);
  f.outward.assign(tracks.size(), 0.0);
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const double fd = m.features[i].last_px.x - camera.cx;
    f.outward[i] = fd < 0.0 ? -1.0 : 1.0;
    if (!tracks[i].tracked) continue;
    const double fc = tracks[i].position.x - camera.cx;
    switch (FunnelLaneVote(fc, fd)) {
      case TurnVote::kLeft:
        ++f.tally.left;
        break;
      case TurnVote::kRight:
        ++f.tally.right;
        break;
      case TurnVote::kStraight:
        ++f.tally.straight;
        break;
    }
    f.error_px[i] =
        bearing ? camera.fx * (std::atan(fc / camera.fx) - std::atan(fd / camera.fx)) : fc - fd;
  }
  return f;
}

MilestoneSwitch::MilestoneSwitch(double hysteresis_px, SwitchError mode, bool remove_rotation)
    : detector_(hysteresis_px), mode_(mode), remove_rotation_(remove_rotation) {}

void MilestoneSwitch::Reset() {
  detector_.Reset();
  fresh_ = true;
  common_ = 0.0;
  accumulated_ = 0.0;
  last_error_.clear();
  last_outward_.clear();
}

double MilestoneSwitch::Term(double error, double outward, double common) const {
  const double e = error - common;
  return mode_ == SwitchError::kMeanAbsolute ? std::abs(e) : outward * e;
}

bool MilestoneSwitch::Update(const FunnelFrame& frame) {
  const std::vector<double>& e = frame.error_px;
  if (fresh_ || last_error_.size() != e.size()) {
    // The start values, over every tracked feature.
    double sum = 0.0;
    int n = 0;
    for (double v : e) {
      if (std::isfinite(v)) {
        sum += v;
        ++n;
      }
    }
    if (n > 0) {
      common_ = remove_rotation_ ? sum / n : 0.0;
      double terms = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i) {
        if (std::isfinite(e[i])) terms += Term(e[i], frame.outward[i], common_);
      }
      accumulated_ = terms / n;
      fresh_ = false;
    }
  } else {
    // Changes over the features tracked in both frames only.
    double shift = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      if (std::isfinite(e[i]) && std::isfinite(last_error_[i])) {
        shift += e[i] - last_error_[i];
        ++n;
      }
    }
    if (n > 0) {
      const double common = remove_rotation_ ? common_ + shift / n : 0.0;
      double change = 0.0;
      for (std::size_t i = 0; i < e.size(); ++i) {
        if (std::isfinite(e[i]) && std::isfinite(last_error_[i])) {
          change += Term(e[i], frame.outward[i], common) -
                    Term(last_error_[i], last_outward_[i], common_);
        }
      }
      accumulated_ += change / n;
      common_ = common;
    }
  }
  last_error_ = e;
  last_outward_ = frame.outward;
  if (fresh_) return false;
  return detector_.Update(error_px());
}

double MilestoneSwitch::error_px() const {
  return mode_ == SwitchError::kMeanAbsolute ? accumulated_ : std::abs(accumulated_);
}

MilestoneProgress ProgressOf(const CameraIntrinsics& camera, const Milestone& m,
                             const std::vector<FeatureTrack>& tracks,
                             const MilestoneProgressOptions& options) {
  std::vector<cv::Point2f> positions;
  std::vector<bool> tracked;
  positions.reserve(tracks.size());
  tracked.reserve(tracks.size());
  for (const FeatureTrack& t : tracks) {
    positions.push_back(t.position);
    tracked.push_back(t.tracked);
  }
  return EstimateMilestoneProgress(camera, m, positions, tracked, options);
}

std::vector<cv::Point2f> ShiftedGuesses(const Milestone& previous,
                                        const std::vector<FeatureTrack>& tracks,
                                        const Milestone& next) {
  std::vector<float> dx, dy;
  for (std::size_t i = 0; i < tracks.size() && i < previous.features.size(); ++i) {
    if (!tracks[i].tracked) continue;
    dx.push_back(tracks[i].position.x - previous.features[i].last_px.x);
    dy.push_back(tracks[i].position.y - previous.features[i].last_px.y);
  }
  cv::Point2f shift(0.0f, 0.0f);
  if (!dx.empty()) {
    const std::size_t mid = dx.size() / 2;
    std::nth_element(dx.begin(), dx.begin() + static_cast<std::ptrdiff_t>(mid), dx.end());
    std::nth_element(dy.begin(), dy.begin() + static_cast<std::ptrdiff_t>(mid), dy.end());
    shift = {dx[mid], dy[mid]};
  }
  std::vector<cv::Point2f> guesses;
  guesses.reserve(next.features.size());
  for (const MilestoneFeature& f : next.features) guesses.push_back(f.first_px + shift);
  return guesses;
}

void CheckRepeatInput(const char* who, const TeachMap& map, const cv::Mat& gray, double t_s,
                      bool started, double last_t_s) {
  if (gray.empty() || gray.type() != CV_8UC1 || gray.size() != map.camera.size()) {
    throw std::invalid_argument(std::string(who) + ": needs a CV_8UC1 image of " +
                                std::to_string(map.camera.width) + "x" +
                                std::to_string(map.camera.height) + " px");
  }
  if (!std::isfinite(t_s) || (started && t_s < last_t_s)) {
    throw std::invalid_argument(std::string(who) + ": time must be finite and not decreasing");
  }
}

std::vector<cv::Point2f> StartGuesses(const Milestone& m, const cv::Mat& gray) {
  const cv::Point2f shift = EstimateImageShift(m.key_image, gray);
  std::vector<cv::Point2f> guesses;
  guesses.reserve(m.features.size());
  for (const MilestoneFeature& f : m.features) guesses.push_back(f.first_px + shift);
  return guesses;
}

}  // namespace detail

FunnelLaneRepeater::FunnelLaneRepeater(TeachMap map, const FunnelLaneOptions& options)
    : map_(std::move(map)), options_(options) {
  options_.Validate();
  if (map_.milestones.empty()) {
    throw std::invalid_argument("FunnelLaneRepeater: the teach map has no milestones");
  }
  if (options_.start_milestone >= static_cast<int>(map_.milestones.size())) {
    throw std::invalid_argument("FunnelLaneRepeater: start_milestone " +
                                std::to_string(options_.start_milestone) + " beyond the map's " +
                                std::to_string(map_.milestones.size()) + " milestones");
  }
  tracks_ = std::make_unique<detail::MilestoneTracks>(options_.tracker);
  switch_ = std::make_unique<detail::MilestoneSwitch>(
      options_.switch_hysteresis_px, options_.switch_error, options_.remove_rotation);
}

FunnelLaneRepeater::~FunnelLaneRepeater() = default;

void FunnelLaneRepeater::StartMilestone(int index, const std::vector<cv::Point2f>& guesses) {
  milestone_ = index;
  const Milestone& m = map_.milestones[static_cast<std::size_t>(index)];
  tracks_->Start(m, curr_pyramid_, guesses);
  switch_->Reset();
  frames_in_milestone_ = 0;
  // Whether the images can tell where the robot is in this milestone at all: the fit
  // of its own destination positions.
  std::vector<cv::Point2f> last;
  for (const MilestoneFeature& f : m.features) last.push_back(f.last_px);
  taught_flow_measurable_ =
      EstimateMilestoneProgress(map_.camera, m, last, std::vector<bool>(last.size(), true),
                                options_.progress)
          .valid;
}

RepeatCommand FunnelLaneRepeater::Update(const cv::Mat& gray, double t_s) {
  detail::CheckRepeatInput("FunnelLaneRepeater::Update", map_, gray, t_s, started_, last_t_s_);
  last_t_s_ = t_s;
  RepeatCommand cmd;
  cmd.milestone = milestone_;
  cmd.features_lost = lost_total_;
  if (status_ != RepeatStatus::kDriving) {
    cmd.status = status_;
    return cmd;
  }

  tracks_->BuildPyramid(gray, &curr_pyramid_);
  if (!started_) {
    StartMilestone(options_.start_milestone,
                   detail::StartGuesses(
                       map_.milestones[static_cast<std::size_t>(options_.start_milestone)], gray));
    started_ = true;
  } else {
    tracks_->Advance(prev_pyramid_, curr_pyramid_);
    cmd.lost = tracks_->CommitLosses();  // the 2D method has no way to find them again
    lost_total_ += cmd.lost;
  }
  ++frames_in_milestone_;

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
  const bool passed = passed_progress && frames_in_milestone_ > options_.min_frames_per_milestone;
  cmd.mean_error_px = switch_->error_px();
  if (passed) {
    if (milestone_ + 1 >= static_cast<int>(map_.milestones.size())) {
      status_ = RepeatStatus::kFinished;
      cmd.status = status_;
      cmd.features_lost = lost_total_;
      std::swap(prev_pyramid_, curr_pyramid_);
      return cmd;
    }
    const Milestone& next = map_.milestones[static_cast<std::size_t>(milestone_ + 1)];
    const std::vector<cv::Point2f> guesses = detail::ShiftedGuesses(*m, tracks_->tracks(), next);
    StartMilestone(milestone_ + 1, guesses);
    cmd.switched = true;
    m = &next;
    frame = detail::EvaluateFunnel(map_.camera, *m, tracks_->tracks(), options_.remove_rotation);
    switch_->Update(frame);
    cmd.mean_error_px = switch_->error_px();
    progress = detail::ProgressOf(map_.camera, *m, tracks_->tracks(), options_.progress);
  }
  if (progress.valid) {
    cmd.progress = progress.progress;
    cmd.heading_error_rad = progress.heading_px / map_.camera.fx;  // > 0: turned left
  }

  cmd.milestone = milestone_;
  cmd.features = static_cast<int>(tracks_->size());
  cmd.tracked = tracks_->tracked();
  cmd.votes_left = frame.tally.left;
  cmd.votes_right = frame.tally.right;
  cmd.votes_straight = frame.tally.straight;
  cmd.features_lost = lost_total_;
  if (cmd.tracked < options_.min_features) {
    cmd.too_few_features = true;
    if (++too_few_frames_ > options_.lost_patience_frames) {
      status_ = RepeatStatus::kLost;
      cmd.status = status_;
      std::swap(prev_pyramid_, curr_pyramid_);
      return cmd;
    }
    cmd.twist.v_mps = options_.forward_speed_mps;  // straight on, hoping to see again
  } else {
    too_few_frames_ = 0;
    cmd.decision = DecideTurn(frame.tally, options_.min_net_vote);
    if (cmd.decision == TurnVote::kStraight && options_.heading_correction && progress.valid &&
        std::abs(progress.heading_px) > options_.heading_deadband_px) {
      cmd.decision = progress.heading_px > 0.0 ? TurnVote::kRight : TurnVote::kLeft;
    }
    cmd.twist.v_mps = options_.forward_speed_mps;
    cmd.twist.yaw_rate_radps =
        static_cast<double>(static_cast<int>(cmd.decision)) * options_.turn_rate_radps;
  }
  std::swap(prev_pyramid_, curr_pyramid_);
  return cmd;
}

}  // namespace trackbed::teach_repeat
