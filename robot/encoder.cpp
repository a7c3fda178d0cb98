// Sprocket encoder options (see encoder.h).
#include "trackbed/robot/encoder.h"

#include "trackbed/common/option_error.h"

namespace trackbed::robot {

void EncoderOptions::Validate() const {
  if (ticks_per_rev < 1) throw OptionError("ticks_per_rev", "must be >= 1");
  option_check::InRange("rate_hz", rate_hz, 100.0, 10000.0);
}

}  // namespace trackbed::robot
