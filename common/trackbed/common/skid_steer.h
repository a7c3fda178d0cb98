// Skid-steer (differential-drive) kinematics of a tracked vehicle: pure functions.
//
// With track speeds v_l, v_r and an effective gauge B_eff = χ·B (the ICR
// expansion factor χ of Martinez et al. 2005 / Mandow et al. 2007; χ = 1 is
// the no-slip ideal): v = (v_r + v_l)/2, ω = (v_r − v_l)/B_eff.
#pragma once

#include <cstdint>

namespace trackbed::kinematics {

struct BodyTwist {
  double v_mps = 0.0;  ///< Forward speed.
  double yaw_rate_radps = 0.0;
};

struct TrackSpeeds {
  double left_mps = 0.0;
  double right_mps = 0.0;
};

/// Body twist from track speeds, for an effective gauge `gauge_m` (> 0).
inline BodyTwist TwistFromTrackSpeeds(const TrackSpeeds& s, double gauge_m) {
  return {(s.right_mps + s.left_mps) / 2.0, (s.right_mps - s.left_mps) / gauge_m};
}

/// Track speeds that realise a body twist, for an effective gauge `gauge_m` (> 0).
inline TrackSpeeds TrackSpeedsFromTwist(const BodyTwist& t, double gauge_m) {
  return {t.v_mps - t.yaw_rate_radps * gauge_m / 2.0, t.v_mps + t.yaw_rate_radps * gauge_m / 2.0};
}

/// Distance [m] the encoders imply for one sample interval: |r (Δφ_l + Δφ_r) / 2|
/// (docs/run_folder.md, `encoder_distance_m`).
inline double EncoderDistanceIncrement(double delta_left_rad, double delta_right_rad,
                                       double sprocket_radius_m) {
  const double d = sprocket_radius_m * (delta_left_rad + delta_right_rad) / 2.0;
  return d < 0 ? -d : d;
}

}  // namespace trackbed::kinematics
