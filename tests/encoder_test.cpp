// The sprocket encoders (robot/encoder.h) keep their own dropout state: in a dropout a
// track's count freezes, the motion meanwhile is lost for good, and counting resumes
// from the frozen value; the other track counts on.
#include "trackbed/robot/encoder.h"

#include <array>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

namespace trackbed::robot {
namespace {

TEST(SprocketEncodersTest, ADropoutFreezesTheCountAndLosesTheMotionMeanwhile) {
  EncoderOptions o;
  o.ticks_per_rev = 1000;
  o.dropouts_s = {{EncoderDropout::Track::kLeft, 0.995, 0.5}};  // samples 1.00 to 1.49 s
  SprocketEncoders encoders(o);
  EXPECT_EQ(encoders.counts(), (std::array<std::int64_t, 2>{0, 0}));
  // Both sprockets turn a revolution a second (1000 counts a second), sampled at 100 Hz.
  std::array<std::int64_t, 2> at_start_of_dropout{}, last{};
  for (int k = 0; k <= 300; ++k) {
    const double t = 0.01 * k;
    const double angle = 2.0 * M_PI * t;
    last = encoders.Sample(t, {angle, angle});
    EXPECT_EQ(last, encoders.counts());
    const std::int64_t shaft = EncoderTicks(angle, o.ticks_per_rev);
    EXPECT_EQ(last[1], shaft) << "t = " << t;  // the right track counts on
    if (k == 99) at_start_of_dropout = last;
    if (k >= 100 && k < 150) {
      EXPECT_EQ(last[0], at_start_of_dropout[0]) << "t = " << t;  // frozen
    }
    if (k < 100) {
      EXPECT_EQ(last[0], shaft) << "t = " << t;
    }
  }
  // After it, the left count lags by what turned in the dropout: samples at 1.00 to
  // 1.49 s lost the motion from 0.99 to 1.49 s, 500 counts.
  EXPECT_EQ(last[1] - last[0], 500);
  EXPECT_EQ(last[1], EncoderTicks(2.0 * M_PI * 3.0, o.ticks_per_rev));
}

TEST(SprocketEncodersTest, WithoutDropoutsTheCountIsTheShaftsAndBothTracksDropTogether) {
  EncoderOptions o;
  o.ticks_per_rev = 4096;
  SprocketEncoders plain(o);
  o.dropouts_s = {{EncoderDropout::Track::kBoth, 0.195, 0.1}};  // samples 0.20 to 0.29 s
  SprocketEncoders both(o);
  for (int k = 0; k <= 50; ++k) {
    const double t = 0.01 * k;
    const std::array<double, 2> angles = {3.0 * t, -2.0 * t};  // forward and backward
    const std::array<std::int64_t, 2> c = plain.Sample(t, angles);
    EXPECT_EQ(c[0], EncoderTicks(angles[0], o.ticks_per_rev));
    EXPECT_EQ(c[1], EncoderTicks(angles[1], o.ticks_per_rev));
    both.Sample(t, angles);
  }
  // Both lost the motion of the samples at 0.20 to 0.29 s (from 0.19 to 0.29 s).
  for (int side = 0; side < 2; ++side) {
    const double rate = side == 0 ? 3.0 : -2.0;
    const std::int64_t lost =
        EncoderTicks(rate * 0.29, o.ticks_per_rev) - EncoderTicks(rate * 0.19, o.ticks_per_rev);
    EXPECT_EQ(plain.counts()[side] - both.counts()[side], lost) << "side " << side;
    EXPECT_NE(lost, 0);
  }
}

}  // namespace
}  // namespace trackbed::robot
