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

}  // namespace trackbed::robot
