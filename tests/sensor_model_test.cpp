// The camera's sensor model: the noise stream is the one its comment describes
// (so images stay reproducible to the bit across refactors), its statistics
// are the configured ones, and it clamps to the 8-bit range.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/robot/encoder.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::robot {
namespace {

std::uint64_t SplitMix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// The model written pixel by pixel from its description in stereo_rig.cpp: a
// table of 65536 Irwin-Hall(4) samples from (seed), indexed by the 16-bit
// quarters of a xorshift64* stream keyed by (seed, frame, camera).
void Reference(double exposure, double noise_std, std::uint64_t seed, std::uint64_t frame,
               int camera, GrayImage* image) {
  std::vector<float> table(1 << 16);
  std::uint64_t state = SplitMix(seed ^ 0x5eed5eedULL);
  const double norm = 1.0 / (65536.0 * std::sqrt(4.0 / 12.0));
  for (float& t : table) {
    state = SplitMix(state);
    const double sum = static_cast<double>((state & 0xffff) + ((state >> 16) & 0xffff) +
                                           ((state >> 32) & 0xffff) + (state >> 48));
    t = static_cast<float>(noise_std * (sum - 2.0 * 65535.0) * norm);
  }
  std::uint64_t x = SplitMix(seed ^ SplitMix(frame * 2 + static_cast<std::uint64_t>(camera))) | 1;
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < image->pixels.size(); ++i) {
    if (i % 4 == 0) {
      x ^= x >> 12;
      x ^= x << 25;
      x ^= x >> 27;
      bits = x * 0x2545f4914f6cdd1dULL;
    }
    const float noise = noise_std > 0.0 ? table[bits & 0xffff] : 0.0f;
    bits >>= 16;
    const float value = static_cast<float>(exposure) * image->pixels[i] + noise + 0.5f;
    image->pixels[i] =
        static_cast<std::uint8_t>(value <= 0.0f ? 0.0f : (value >= 255.0f ? 255.0f : value));
  }
}

GrayImage Ramp(int width, int height) {
  GrayImage img;
  img.width = width;
  img.height = height;
  img.pixels.resize(static_cast<std::size_t>(width) * height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = (i * 7) % 256;
  return img;
}

TEST(SensorModelTest, GivesTheBytesOfItsDescription) {
  struct Case {
    int width, height;
    double exposure, noise_std;
    std::uint64_t seed, frame;
    int camera;
  };
  // Sizes that are and are not multiples of four pixels; no noise; gain above and below 1.
  for (const Case& c : {Case{640, 480, 1.0, 1.0, 1, 0, 0}, Case{640, 480, 1.0, 1.0, 1, 37, 1},
                        Case{17, 19, 1.3, 0.0, 5, 2, 0}, Case{33, 7, 0.8, 2.5, 9, 1000, 1},
                        Case{3, 1, 1.0, 4.0, 2, 3, 0}}) {
    GrayImage a = Ramp(c.width, c.height), b = a;
    ApplySensorModel(c.exposure, c.noise_std, c.seed, c.frame, c.camera, &a);
    Reference(c.exposure, c.noise_std, c.seed, c.frame, c.camera, &b);
    EXPECT_EQ(a.pixels, b.pixels) << c.width << "x" << c.height << " frame " << c.frame;
  }
}

TEST(SensorModelTest, NoiseHasTheConfiguredSpreadAndDependsOnFrameAndCamera) {
  GrayImage flat = Ramp(640, 480);
  std::fill(flat.pixels.begin(), flat.pixels.end(), 100);
  GrayImage a = flat, b = flat, c = flat, again = flat;
  ApplySensorModel(1.0, 3.0, 7, 10, 0, &a);
  ApplySensorModel(1.0, 3.0, 7, 10, 1, &b);  // the other camera
  ApplySensorModel(1.0, 3.0, 7, 11, 0, &c);  // the next frame
  ApplySensorModel(1.0, 3.0, 7, 10, 0, &again);
  EXPECT_EQ(a.pixels, again.pixels);
  EXPECT_NE(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
  double sum = 0, sum2 = 0, same_ab = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = a.pixels[i] - 100.0;
    sum += d;
    sum2 += d * d;
    same_ab += a.pixels[i] == b.pixels[i];
  }
  const double n = static_cast<double>(a.pixels.size());
  const double mean = sum / n, std = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.02);
  // Rounding to whole grey levels adds 1/12 to the variance.
  EXPECT_NEAR(std, std::sqrt(9.0 + 1.0 / 12.0), 0.03);
  EXPECT_LT(same_ab / n, 0.2);  // independent draws: P(equal) is about 0.13 at 3 grey levels
}

TEST(SensorModelTest, ClampsToTheEightBitRange) {
  GrayImage img = Ramp(64, 64);
  ApplySensorModel(3.0, 1.0, 1, 0, 0, &img);
  int saturated = 0;
  for (std::uint8_t p : img.pixels) saturated += p == 255;
  EXPECT_GT(saturated, 64 * 64 / 2);  // 3 x grey over 85 saturates: two thirds of the ramp
  GrayImage dark = Ramp(64, 64);
  std::fill(dark.pixels.begin(), dark.pixels.end(), 0);
  ApplySensorModel(1.0, 5.0, 1, 0, 0, &dark);
  int zeros = 0;
  for (std::uint8_t p : dark.pixels) zeros += p == 0;
  EXPECT_GT(zeros, 64 * 64 * 4 / 10);  // negative noise clamps to 0: about half
}

// The encoder counts as an incremental encoder does: floor(angle / 2π · ticks), so a
// count never runs ahead of the shaft, backward motion counts down through zero without
// a dead band (truncation toward zero would show 0 for the whole first tick backward),
// and one tick is the quantum either way.
TEST(EncoderTest, QuantisesByFloorInBothDirections) {
  constexpr int kTicks = 4096;
  const double tick = 2.0 * M_PI / kTicks;
  EXPECT_EQ(EncoderTicks(0.0, kTicks), 0);
  EXPECT_EQ(EncoderTicks(0.5 * tick, kTicks), 0);
  EXPECT_EQ(EncoderTicks(-0.5 * tick, kTicks), -1);
  EXPECT_EQ(EncoderTicks(-1e-9, kTicks), -1);
  EXPECT_EQ(EncoderTicks(2.0 * M_PI + 0.5 * tick, kTicks), kTicks);
  EXPECT_EQ(EncoderTicks(-2.0 * M_PI - 0.5 * tick, kTicks), -kTicks - 1);
  for (int i = -3000; i <= 3000; ++i) {
    const double angle = i * 0.00731;  // ±21.9 rad, off the tick grid
    const std::int64_t t = EncoderTicks(angle, kTicks);
    EXPECT_LE(TicksToAngle(t, kTicks), angle + 1e-12) << angle;
    EXPECT_GT(TicksToAngle(t + 1, kTicks), angle - 1e-12) << angle;
    // Forward and backward by the same angle: counts mirror up to the floor's tick.
    const std::int64_t back = EncoderTicks(-angle, kTicks);
    EXPECT_TRUE(t + back == 0 || t + back == -1) << angle;
  }
}

}  // namespace
}  // namespace trackbed::robot
