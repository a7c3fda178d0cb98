// Status names and the repeater factory (see teach_repeat.h).
#include "trackbed/teach_repeat/teach_repeat.h"

#include <stdexcept>

#include "trackbed/teach_repeat/funnel_lane_controller.h"
#include "trackbed/teach_repeat/milestone_localizer_3d.h"

namespace trackbed::teach_repeat {

const char* ToString(RepeatStatus status) {
  switch (status) {
    case RepeatStatus::kDriving:
      return "driving";
    case RepeatStatus::kFinished:
      return "finished";
    case RepeatStatus::kLost:
      return "lost";
  }
  return "unknown";
}

const char* ToString(TurnVote vote) {
  switch (vote) {
    case TurnVote::kLeft:
      return "left";
    case TurnVote::kStraight:
      return "straight";
    case TurnVote::kRight:
      return "right";
  }
  return "unknown";
}

std::unique_ptr<Repeater> MakeRepeater(const std::string& method, TeachMap map,
                                       const FunnelLaneOptions& options_2d,
                                       const Localizer3dOptions& options_3d) {
  if (method == "2d") return std::make_unique<FunnelLaneRepeater>(std::move(map), options_2d);
  if (method == "3d") return std::make_unique<MilestoneLocalizer3d>(std::move(map), options_3d);
  throw std::invalid_argument("MakeRepeater: method must be \"2d\" or \"3d\" (got \"" + method +
                              "\")");
}

}  // namespace trackbed::teach_repeat
