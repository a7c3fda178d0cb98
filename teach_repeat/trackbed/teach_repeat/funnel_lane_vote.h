// The funnel-lane rules (Chen & Birchfield 2006; Choi & Ha 2011 eq. 1) and their
// bang-bang vote, shared by the 2D repeater (funnel_lane_controller.h, whose file comment
// states the rules and our readings) and the 3D repeater's fallback
// (milestone_localizer_3d.h).
#pragma once

#include <vector>

#include "trackbed/teach_repeat/teach_repeat.h"

namespace trackbed::teach_repeat {

/// The funnel-lane rule for one feature (funnel_lane_controller.h): f_c, f_d [px] relative
/// to the principal point.
TurnVote FunnelLaneVote(double f_current_px, double f_destination_px);

/// Votes of all features.
struct VoteTally {
  int left = 0, right = 0, straight = 0;
  int total() const { return left + right + straight; }
};

/// Bang-bang decision from a tally (funnel_lane_controller.h); straight when there are no
/// votes. min_net_vote in [0, 1).
TurnVote DecideTurn(const VoteTally& tally, double min_net_vote);

namespace detail {

/// One frame of the funnel-lane rules over a milestone's tracked features: the votes
/// that steer, and the x-errors that the milestone switch (milestone_switch.h) follows.
struct FunnelFrame {
  VoteTally tally;
  /// Per feature: its x-error e_i (f_c − f_d, or the bearing error in pixels at the
  /// image centre) [px]; NaN where the feature is not tracked.
  std::vector<double> error_px;
  /// Per feature: +1 if its destination is right of the centre, −1 if left ("outward").
  std::vector<double> outward;
};

}  // namespace detail
}  // namespace trackbed::teach_repeat
