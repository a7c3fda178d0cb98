// One teach & repeat run (Choi & Ha 2011; docs/teach_repeat.md): the teach pass
// drives the scenario's path (the "manual" drive) and records the left images into a
// teach map; the repeat pass starts near the taught start and follows the route from
// the images alone. Both passes are full run folders: DIR/teach/ and DIR itself, with
// the map in DIR/teach_map/ and the score in DIR/metrics.json `teach_repeat`.
#pragma once

#include <filesystem>

#include "trackbed/runner/run_metrics.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// Teaches (unless teach_repeat.map names a map to load) and repeats `scenario` into
/// `dir`. A map loaded this way is scored against the taught ground truth in the
/// teach/ folder beside it when there is one.
RunMetrics RunTeachRepeat(const scenario::Scenario& scenario, const std::filesystem::path& dir);

}  // namespace trackbed::runner
