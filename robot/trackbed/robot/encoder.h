// Sprocket encoders: quantized shaft angle, sampled at a fixed rate.
#pragma once

#include <cmath>
#include <cstdint>

namespace trackbed::robot {

struct EncoderOptions {
  /// Counts per sprocket revolution (after quadrature decoding), >= 1.
  int ticks_per_rev = 4096;
  /// Sampling rate [Hz], >= 100 (docs/scenario_format.md, `robot.encoders.rate_hz`).
  double rate_hz = 100.0;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("ticks_per_rev", &ticks_per_rev);
    a->Visit("rate_hz", &rate_hz);
  }
};

/// The count an incremental encoder shows at shaft angle `angle_rad` (counted
/// from zero at start): floor(angle / 2π · ticks_per_rev).
inline std::int64_t EncoderTicks(double angle_rad, int ticks_per_rev) {
  return static_cast<std::int64_t>(std::floor(angle_rad / (2.0 * M_PI) * ticks_per_rev));
}

/// Shaft angle [rad] a tick count stands for.
inline double TicksToAngle(std::int64_t ticks, int ticks_per_rev) {
  return static_cast<double>(ticks) * 2.0 * M_PI / ticks_per_rev;
}

}  // namespace trackbed::robot
