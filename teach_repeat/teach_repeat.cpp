// Status and vote names (see teach_repeat.h).
#include "trackbed/teach_repeat/teach_repeat.h"

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

}  // namespace trackbed::teach_repeat
