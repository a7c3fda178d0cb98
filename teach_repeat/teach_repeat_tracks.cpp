// What the repeaters read from the active milestone's feature tracks (see
// teach_repeat_tracks.h).
#include "teach_repeat_tracks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trackbed/teach_repeat/teach_repeat_geometry.h"

namespace trackbed::teach_repeat::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

FunnelFrame EvaluateFunnel(const geometry::PinholeCamera& camera, const Milestone& m,
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

MilestoneProgress ProgressOf(const geometry::PinholeCamera& camera, const Milestone& m,
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

std::vector<cv::Point2f> StartGuesses(const Milestone& m, const cv::Mat& gray) {
  const cv::Point2f shift = EstimateImageShift(m.key_image, gray);
  std::vector<cv::Point2f> guesses;
  guesses.reserve(m.features.size());
  for (const MilestoneFeature& f : m.features) guesses.push_back(f.first_px + shift);
  return guesses;
}

}  // namespace trackbed::teach_repeat::detail
