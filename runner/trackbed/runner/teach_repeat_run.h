// One teach & repeat run (Choi & Ha 2011; docs/teach_repeat.md): the teach pass
// drives the scenario's path (the "manual" drive) and records the left images into a
// teach map; the repeat pass starts near the taught start and follows the route from
// the images alone. Both passes are full run folders: DIR/teach/ and DIR itself, with
// the map in DIR/teach_map/ and the score in DIR/metrics.json `teach_repeat`.
#pragma once

#include <filesystem>

#include "trackbed/runner/run_metrics.h"
#include "trackbed/runner/run_observers.h"
#include "trackbed/scenario/scenario.h"
#include "trackbed/teach_repeat/funnel_lane_controller.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/milestone_localizer_3d.h"

namespace trackbed::runner {

/// Teaches (unless teach_repeat.map names a map to load) and repeats `scenario` into
/// `dir`. A map loaded this way is scored against the taught ground truth in the
/// teach/ folder beside it when there is one. `observers` are called in both passes,
/// after the run's own (the repeat pass's times start again from 0).
RunMetrics RunTeachRepeat(const scenario::Scenario& scenario, const std::filesystem::path& dir,
                          const RunObservers& observers = {});

/// The options a run of `tr` builds, from the section's structs: the teach pass's
/// milestones (mode: `method`) …
teach_repeat::MilestoneBuilderOptions MilestoneBuilderOptionsOf(
    const scenario::TeachRepeatSpec& tr);
/// … and the repeaters', whose speeds are `repeat_speed_mps` and `repeat_turn_rate_deg_s`.
teach_repeat::FunnelLaneOptions FunnelLaneOptionsOf(const scenario::TeachRepeatSpec& tr);
teach_repeat::Localizer3dOptions Localizer3dOptionsOf(const scenario::TeachRepeatSpec& tr);

}  // namespace trackbed::runner
