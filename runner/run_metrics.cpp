// Run metrics (see run_metrics.h).
#include "trackbed/runner/run_metrics.h"

#include <algorithm>
#include <cmath>

#include "trackbed/common/skid_steer.h"
#include "trackbed/robot/encoder.h"

namespace trackbed::runner {

MetricsAccumulator::MetricsAccumulator(double sprocket_radius_m, double track_gauge_m,
                                       int ticks_per_rev)
    : r_(sprocket_radius_m), gauge_(track_gauge_m), ticks_per_rev_(ticks_per_rev) {
  m_.min_com_height_m = 1e300;
}

void MetricsAccumulator::Add(const RunSample& s, double terrain_height_m) {
  m_.sim_time_s = s.t_s;
  m_.min_com_height_m =
      std::min(m_.min_com_height_m, s.chassis.T_world_body.translation().z() - terrain_height_m);
  for (int side = 0; side < 2; ++side) {
    const robot::TrackState& ts = s.tracks[side];
    if (std::abs(ts.track_speed_mps) <= 0.05) continue;
    const double ratio = (ts.track_speed_mps - ts.ground_speed_mps) / ts.track_speed_mps;
    for (SlipStats* st : {&m_.slip[side], &m_.slip_by_material[s.material ? *s.material : ""]}) {
      st->sum_abs_ratio += std::abs(ratio);
      st->sum_ratio += ratio;
      st->sum_abs_velocity_mps += std::abs(ts.slip_velocity_mps);
      ++st->samples;
    }
  }
  if (has_previous_) {
    const double dt = s.t_s - previous_.t_s;
    m_.distance_m +=
        (s.chassis.T_world_body.translation() - previous_.chassis.T_world_body.translation())
            .norm();
    const double dl = robot::TicksToAngle(s.ticks[0] - previous_.ticks[0], ticks_per_rev_);
    const double dr = robot::TicksToAngle(s.ticks[1] - previous_.ticks[1], ticks_per_rev_);
    m_.encoder_distance_m += kinematics::EncoderDistanceIncrement(dl, dr, r_);
    if (dt > 0) {
      // True yaw rate about the body z axis, from the world angular velocity.
      const Eigen::Vector3d z = s.chassis.T_world_body.linear().col(2);
      if (!icr_) icr_.emplace(std::max(1, static_cast<int>(std::lround(1.0 / dt))));
      icr_->Add({r_ * (dr - dl) / (gauge_ * dt), s.chassis.omega_world.dot(z)});
    }
  }
  previous_ = s;
  has_previous_ = true;
}

RunMetrics MetricsAccumulator::Metrics() const {
  RunMetrics m = m_;
  m.icr = icr_ ? icr_->Fit() : estimation::FitIcrExpansion({});
  if (!has_previous_) m.min_com_height_m = 0.0;
  return m;
}

}  // namespace trackbed::runner
