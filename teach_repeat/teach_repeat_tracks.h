// Private to trackbed::teach_repeat: the active milestone's feature tracks during a repeat,
// shared by the 2D and the 3D repeater (milestone_repeater.h), and what the repeaters read
// from them: the funnel-lane votes and x-errors, the progress through the milestone, and
// where to start the tracks of a milestone that becomes active.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "trackbed/perception/feature_tracker.h"
#include "trackbed/teach_repeat/funnel_lane_vote.h"
#include "trackbed/teach_repeat/milestone_switch.h"
#include "trackbed/teach_repeat/teach_map.h"

namespace trackbed::teach_repeat::detail {

/// Per-feature state of the active milestone.
///
/// Counting losses. A tracked feature that KLT (or the reprojection check) drops in a
/// frame is first a pending loss: if patch matching finds it again in the same frame it
/// was never out of sight (its KLT window merely touched an occluder's edge), and neither
/// a loss nor a recovery is counted. A loss is counted when the feature is still lost at
/// the end of the frame (CommitLosses); finding such a feature again later is a
/// recovery. Features that the start of a milestone could not find are lost but
/// uncounted, and finding them is not a recovery.
struct FeatureTrack {
  bool tracked = false;       ///< position is valid in the current image
  bool pending_loss = false;  ///< dropped in this frame, not yet counted
  bool lost_counted = false;  ///< lost, and the loss was counted
  cv::Point2f position;       ///< in the current image [px], when tracked
};

/// What MilestoneTracks::Recover found.
enum class Found { kReacquired, kRecovered, kFound };

/// KLT tracks of one milestone's features. Not copyable.
class MilestoneTracks {
 public:
  explicit MilestoneTracks(const perception::FeatureTrackerOptions& options) : tracker_(options) {}
  MilestoneTracks(const MilestoneTracks&) = delete;
  MilestoneTracks& operator=(const MilestoneTracks&) = delete;

  void BuildPyramid(const cv::Mat& gray, perception::TrackingPyramid* pyramid) const {
    tracker_.BuildPyramid(gray, pyramid);
  }

  /// Starts milestone `m`: its features' first_px are tracked by KLT from the key image
  /// into the current image, starting at `guesses` (one per feature). Returns the number
  /// tracked.
  int Start(const Milestone& m, const perception::TrackingPyramid& current,
            const std::vector<cv::Point2f>& guesses) {
    tracker_.BuildPyramid(m.key_image, &key_pyramid_);
    first_px_.clear();
    for (const MilestoneFeature& f : m.features) first_px_.push_back(f.first_px);
    scratch_ = guesses;
    tracker_.Track(key_pyramid_, current, first_px_, &scratch_, &status_, !first_px_.empty());
    tracks_.assign(first_px_.size(), FeatureTrack{});
    int n = 0;
    std::vector<float> dx, dy;
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      if (status_[i] != perception::TrackStatus::kTracked) continue;
      tracks_[i].tracked = true;
      tracks_[i].position = scratch_[i];
      dx.push_back(scratch_[i].x - guesses[i].x);
      dy.push_back(scratch_[i].y - guesses[i].y);
      ++n;
    }
    // Second pass for the features the first missed, from their guesses moved by the
    // median correction of those found: a guess that is off by more than KLT's capture
    // range for most features (the coarse pyramid levels of a fine texture carry little)
    // is corrected by the few that were caught.
    if (n >= 3 && n < static_cast<int>(tracks_.size())) {
      const std::size_t mid = dx.size() / 2;
      std::nth_element(dx.begin(), dx.begin() + static_cast<std::ptrdiff_t>(mid), dx.end());
      std::nth_element(dy.begin(), dy.begin() + static_cast<std::ptrdiff_t>(mid), dy.end());
      const cv::Point2f correction(dx[mid], dy[mid]);
      index_.clear();
      from_.clear();
      retry_.clear();
      for (std::size_t i = 0; i < tracks_.size(); ++i) {
        if (tracks_[i].tracked) continue;
        index_.push_back(i);
        from_.push_back(first_px_[i]);
        retry_.push_back(guesses[i] + correction);
      }
      tracker_.Track(key_pyramid_, current, from_, &retry_, &status_, true);
      for (std::size_t k = 0; k < index_.size(); ++k) {
        if (status_[k] != perception::TrackStatus::kTracked) continue;
        tracks_[index_[k]].tracked = true;
        tracks_[index_[k]].position = retry_[k];
        ++n;
      }
    }
    return n;
  }

  /// Tracks the tracked features from `prev` into `curr`. Returns the number dropped
  /// (pending losses).
  int Advance(const perception::TrackingPyramid& prev, const perception::TrackingPyramid& curr) {
    index_.clear();
    from_.clear();
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      if (!tracks_[i].tracked) continue;
      index_.push_back(i);
      from_.push_back(tracks_[i].position);
    }
    if (index_.empty()) return 0;
    tracker_.Track(prev, curr, from_, &scratch_, &status_);
    int lost = 0;
    for (std::size_t k = 0; k < index_.size(); ++k) {
      FeatureTrack& t = tracks_[index_[k]];
      if (status_[k] == perception::TrackStatus::kTracked) {
        t.position = scratch_[k];
      } else {
        Lose(index_[k]);
        ++lost;
      }
    }
    return lost;
  }

  /// Marks a tracked feature lost (a pending loss).
  void Lose(std::size_t i) {
    tracks_[i].tracked = false;
    tracks_[i].pending_loss = true;
  }

  /// Counts the pending losses of this frame; returns their number.
  int CommitLosses() {
    int n = 0;
    for (FeatureTrack& t : tracks_) {
      if (!t.pending_loss) continue;
      t.pending_loss = false;
      t.lost_counted = true;
      ++n;
    }
    return n;
  }

  /// Marks a tracked feature lost without counting the loss (it was never tracked
  /// properly: a wrong match at the start of a milestone).
  void Forget(std::size_t i) {
    tracks_[i].tracked = false;
    tracks_[i].pending_loss = false;
  }

  /// Marks a lost feature found at `position`.
  Found Recover(std::size_t i, const cv::Point2f& position) {
    FeatureTrack& t = tracks_[i];
    const Found found = t.pending_loss   ? Found::kReacquired
                        : t.lost_counted ? Found::kRecovered
                                         : Found::kFound;
    t.tracked = true;
    t.pending_loss = false;
    t.lost_counted = false;
    t.position = position;
    return found;
  }

  const std::vector<FeatureTrack>& tracks() const { return tracks_; }
  std::size_t size() const { return tracks_.size(); }
  int tracked() const {
    int n = 0;
    for (const FeatureTrack& t : tracks_) n += t.tracked ? 1 : 0;
    return n;
  }
  const perception::FeatureTrackerOptions& options() const { return tracker_.options(); }

 private:
  perception::FeatureTracker tracker_;
  perception::TrackingPyramid key_pyramid_;
  std::vector<FeatureTrack> tracks_;
  std::vector<cv::Point2f> first_px_, from_, scratch_, retry_;
  std::vector<std::size_t> index_;
  std::vector<perception::TrackStatus> status_;
};

/// Votes and x-errors of the tracked features of `m`. `bearing`: errors as bearing
/// differences.
FunnelFrame EvaluateFunnel(const geometry::PinholeCamera& camera, const Milestone& m,
                           const std::vector<FeatureTrack>& tracks, bool bearing);

/// EstimateMilestoneProgress over the tracked features of `m`.
MilestoneProgress ProgressOf(const geometry::PinholeCamera& camera, const Milestone& m,
                             const std::vector<FeatureTrack>& tracks,
                             const MilestoneProgressOptions& options);

/// Guesses for the first milestone of a repeat: the key-image positions moved by the
/// global shift between the key image and the current one (EstimateImageShift).
std::vector<cv::Point2f> StartGuesses(const Milestone& m, const cv::Mat& gray);

/// Guesses for a new milestone's features in the current image: their key-image
/// positions moved by the median displacement (current − last_px) of the previous
/// milestone's tracked features (zero if none).
std::vector<cv::Point2f> ShiftedGuesses(const Milestone& previous,
                                        const std::vector<FeatureTrack>& tracks,
                                        const Milestone& next);

}  // namespace trackbed::teach_repeat::detail
