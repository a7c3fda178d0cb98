// The repeater factory (see repeater_factory.h).
#include "trackbed/teach_repeat/repeater_factory.h"

#include <stdexcept>
#include <utility>

namespace trackbed::teach_repeat {

std::unique_ptr<Repeater> MakeRepeater(TeachMode method, TeachMap map,
                                       const FunnelLaneOptions& options_2d,
                                       const Localizer3dOptions& options_3d) {
  if (method == TeachMode::k3d) {
    return std::make_unique<MilestoneLocalizer3d>(std::move(map), options_3d);
  }
  return std::make_unique<FunnelLaneRepeater>(std::move(map), options_2d);
}

std::unique_ptr<Repeater> MakeRepeater(const std::string& method, TeachMap map,
                                       const FunnelLaneOptions& options_2d,
                                       const Localizer3dOptions& options_3d) {
  for (TeachMode mode : {TeachMode::k2d, TeachMode::k3d}) {
    if (method == ToString(mode)) return MakeRepeater(mode, std::move(map), options_2d, options_3d);
  }
  throw std::invalid_argument("MakeRepeater: method must be \"2d\" or \"3d\" (got \"" + method +
                              "\")");
}

}  // namespace trackbed::teach_repeat
