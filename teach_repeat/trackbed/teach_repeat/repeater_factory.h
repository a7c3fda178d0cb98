// A repeater by name: the one place that knows both repeaters, so that neither the
// shared types (teach_repeat.h) nor a repeater needs the other.
#pragma once

#include <memory>
#include <string>

#include "trackbed/teach_repeat/funnel_lane_controller.h"
#include "trackbed/teach_repeat/milestone_localizer_3d.h"
#include "trackbed/teach_repeat/teach_map.h"
#include "trackbed/teach_repeat/teach_repeat.h"

namespace trackbed::teach_repeat {

/// A repeater for `method` k2d (FunnelLaneRepeater) or k3d (MilestoneLocalizer3d) with
/// the given options. Throws std::invalid_argument for an empty map or invalid options
/// (OptionError).
std::unique_ptr<Repeater> MakeRepeater(TeachMode method, TeachMap map,
                                       const FunnelLaneOptions& options_2d,
                                       const Localizer3dOptions& options_3d);

/// As above, for the method named "2d" or "3d" (ToString(TeachMode)); throws
/// std::invalid_argument for another name.
std::unique_ptr<Repeater> MakeRepeater(const std::string& method, TeachMap map,
                                       const FunnelLaneOptions& options_2d,
                                       const Localizer3dOptions& options_3d);

}  // namespace trackbed::teach_repeat
