// Sprocket encoders: quantized shaft angle, sampled at a fixed rate.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace trackbed::robot {

/// A fault: one track's encoder (or both) stops counting for a while, as a loose
/// connector or a failed channel does. The count freezes and the motion meanwhile is
/// lost for good: counting resumes from the frozen value.
struct EncoderDropout {
  enum class Track { kLeft, kRight, kBoth };
  Track track = Track::kBoth;  ///< left, right or both
  double start_s = 0.0;        ///< when it starts [s], >= 0
  double duration_s = 0.0;     ///< how long [s], > 0

  /// Whether the dropout holds track `side` (0 left, 1 right) at `t_s`: start_s <= t_s <
  /// start_s + duration_s.
  bool Holds(int side, double t_s) const;

  template <class Archive>
  void Serialize(Archive* a) {
    a->VisitEnum("track", &track,
                 {{"left", Track::kLeft}, {"right", Track::kRight}, {"both", Track::kBoth}});
    a->Visit("start_s", &start_s);
    a->Visit("duration_s", &duration_s);
  }
};

struct EncoderOptions {
  /// Counts per sprocket revolution (after quadrature decoding), >= 1.
  int ticks_per_rev = 4096;
  /// Sampling rate [Hz], >= 100 (docs/scenario_format.md, `robot.encoders.rate_hz`).
  double rate_hz = 100.0;
  /// Faults: spans in which a track's count freezes (EncoderDropout). Empty: none.
  std::vector<EncoderDropout> dropouts_s;

  void Validate() const;
  /// Whether track `side` (0 left, 1 right) is in a dropout at `t_s`.
  bool InDropout(int side, double t_s) const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("ticks_per_rev", &ticks_per_rev);
    a->Visit("rate_hz", &rate_hz);
    a->Visit("dropouts_s", &dropouts_s);
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

/// The two tracks' sprocket encoders (0 left, 1 right) as they count: the shaft's count,
/// frozen in a dropout (EncoderOptions::dropouts_s), the motion meanwhile lost for good.
/// Holds what each has lost so far. Not copyable.
class SprocketEncoders {
 public:
  explicit SprocketEncoders(const EncoderOptions& options);
  SprocketEncoders(const SprocketEncoders&) = delete;
  SprocketEncoders& operator=(const SprocketEncoders&) = delete;

  /// The counts at `t_s` (samples in time order) with the sprockets turned by
  /// `sprocket_angle_rad` (left, right; since the start) [rad].
  std::array<std::int64_t, 2> Sample(double t_s, const std::array<double, 2>& sprocket_angle_rad);
  /// The last sample's counts (0, 0 before the first).
  const std::array<std::int64_t, 2>& counts() const { return counts_; }
  const EncoderOptions& options() const { return options_; }

 private:
  EncoderOptions options_;
  std::array<std::int64_t, 2> last_shaft_ = {0, 0};  // the shaft's count at the last sample
  std::array<std::int64_t, 2> lost_ = {0, 0};        // counts lost in dropouts so far
  std::array<std::int64_t, 2> counts_ = {0, 0};
};

}  // namespace trackbed::robot
