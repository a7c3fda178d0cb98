// Sprocket encoder options (see encoder.h).
#include "trackbed/robot/encoder.h"

#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::robot {

bool EncoderDropout::Holds(int side, double t_s) const {
  const bool track_matches = track == Track::kBoth || (track == Track::kLeft && side == 0) ||
                             (track == Track::kRight && side == 1);
  return track_matches && t_s >= start_s && t_s < start_s + duration_s;
}

void EncoderOptions::Validate() const {
  if (ticks_per_rev < 1) throw OptionError("ticks_per_rev", "must be >= 1");
  option_check::InRange("rate_hz", rate_hz, 100.0, 10000.0);
  for (std::size_t k = 0; k < dropouts_s.size(); ++k) {
    const EncoderDropout& d = dropouts_s[k];
    const std::string where = "dropouts_s[" + std::to_string(k) + "].";
    option_check::NonNegative((where + "start_s").c_str(), d.start_s);
    option_check::Positive((where + "duration_s").c_str(), d.duration_s);
  }
}

bool EncoderOptions::InDropout(int side, double t_s) const {
  for (const EncoderDropout& d : dropouts_s) {
    if (d.Holds(side, t_s)) return true;
  }
  return false;
}

SprocketEncoders::SprocketEncoders(const EncoderOptions& options) : options_(options) {}

std::array<std::int64_t, 2> SprocketEncoders::Sample(
    double t_s, const std::array<double, 2>& sprocket_angle_rad) {
  for (int side = 0; side < 2; ++side) {
    // In a dropout the count freezes, and what the shaft turns meanwhile is lost.
    const std::int64_t shaft = EncoderTicks(sprocket_angle_rad[side], options_.ticks_per_rev);
    if (options_.InDropout(side, t_s)) lost_[side] += shaft - last_shaft_[side];
    last_shaft_[side] = shaft;
    counts_[side] = shaft - lost_[side];
  }
  return counts_;
}

}  // namespace trackbed::robot
