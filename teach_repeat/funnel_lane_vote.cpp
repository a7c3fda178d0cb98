// The funnel-lane rules and the vote (see funnel_lane_vote.h).
#include "trackbed/teach_repeat/funnel_lane_vote.h"

namespace trackbed::teach_repeat {

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

}  // namespace trackbed::teach_repeat
