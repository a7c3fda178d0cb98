// The scenario's `drive` section as a commander: a timed script of track speeds or
// body twists, or pure pursuit along waypoints (following ground truth, as a
// teleoperator or a line-following test rig would). A pose path drives nothing (its
// carrier moves itself, robot/pose_path_carrier.h): the driver only ends the run when
// the carrier reaches the path's end.
#pragma once

#include <cstddef>
#include <optional>

#include "trackbed/navigation/pure_pursuit.h"
#include "trackbed/runner/commander.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

class PathDriver : public Commander {
 public:
  /// `nominal_gauge_m` turns twists into track speeds; `pose_path_end_s`, for a pose
  /// path, is when its carrier reaches the end.
  PathDriver(const scenario::DriveSpec& spec, double nominal_gauge_m, double pose_path_end_s = 0.0);

  double period_s() const override { return 1.0 / spec_.rate_hz; }
  /// The script's command in force at t_s, or pure pursuit's; a path that is done ends
  /// the run ("path finished").
  ControlOutput Update(const ControlInput& input) override;

 private:
  scenario::DriveSpec spec_;
  double gauge_;
  std::optional<navigation::PurePursuit> follower_;
  std::size_t next_ = 0;  // the first script command not yet in force
  double pose_path_end_s_ = 0.0;
};

}  // namespace trackbed::runner
