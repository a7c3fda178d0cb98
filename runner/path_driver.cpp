// The scenario's drive as a commander (see path_driver.h).
#include "trackbed/runner/path_driver.h"

#include <cmath>

namespace trackbed::runner {

PathDriver::PathDriver(const scenario::DriveSpec& spec, double nominal_gauge_m,
                       double pose_path_end_s)
    : spec_(spec), gauge_(nominal_gauge_m), pose_path_end_s_(pose_path_end_s) {
  if (spec_.mode == scenario::DriveSpec::Mode::kPath) {
    follower_.emplace(spec_.pursuit, spec_.waypoints, spec_.closed, spec_.laps);
  }
}

ControlOutput PathDriver::Update(const ControlInput& input) {
  ControlOutput out;
  // The start standstill: zero track speeds, then the drive on a clock started at its end.
  if (input.t_s < spec_.start_standstill_s - 1e-9) return out;
  const double t_drive = input.t_s - spec_.start_standstill_s;
  if (spec_.mode == scenario::DriveSpec::Mode::kPosePath) {
    if (input.t_s >= pose_path_end_s_) out.stop_reason = "path finished";
    return out;
  }
  if (follower_) {
    const Eigen::Isometry3d& T = input.T_world_body;
    const double yaw = std::atan2(T.linear()(1, 0), T.linear()(0, 0));
    const navigation::PurePursuitCommand c =
        follower_->Update({T.translation().x(), T.translation().y(), yaw});
    if (c.finished) out.stop_reason = "path finished";
    out.tracks = kinematics::TrackSpeedsFromTwist(c.twist, gauge_);
    return out;
  }
  while (next_ < spec_.script.size() && spec_.script[next_].t_s <= t_drive + 1e-9) ++next_;
  if (next_ == 0) return out;
  const scenario::DriveCommand& c = spec_.script[next_ - 1];
  out.tracks = c.track_speeds
                   ? kinematics::TrackSpeeds{c.left_mps, c.right_mps}
                   : kinematics::TrackSpeedsFromTwist({c.v_mps, c.yaw_rate_radps}, gauge_);
  return out;
}

}  // namespace trackbed::runner
