// The image sensor in electrons (robot/image_sensor.h): a photon-transfer test (noise
// variance against mean grey level follows shot + read noise through the conversion
// gain), vignetting at the corners, a fixed pattern fixed per camera, images
// reproducible from (seed, frame, camera).
#include "trackbed/robot/image_sensor.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/random.h"
#include "trackbed/common/split_mix.h"

namespace trackbed::robot {
namespace {

PhotometricOptions Sensor(double full_well, double read_noise) {
  PhotometricOptions o;
  o.enabled = true;
  o.full_well_e = full_well;
  o.read_noise_e = read_noise;
  o.prnu_std = 0.0;
  o.dsnu_std_e = 0.0;
  o.adc_bits = 12;
  o.vignetting_corner = 1.0;
  o.gain = 1.0;
  return o;
}

GrayImage Flat(int grey) {
  GrayImage g;
  g.width = 320;
  g.height = 240;
  g.pixels.assign(static_cast<std::size_t>(g.width) * g.height, static_cast<std::uint8_t>(grey));
  return g;
}

struct Moments {
  double mean = 0.0, variance = 0.0;
};

// Mean and variance of the difference of two frames (the fixed pattern cancels), the
// photon-transfer method of EMVA 1288: variance = var(a − b) / 2.
Moments FrameMoments(const ImageSensor& sensor, int grey, double exposure) {
  GrayImage a = Flat(grey), b = Flat(grey);
  sensor.Apply(exposure, 7, 1, &a);
  sensor.Apply(exposure, 7, 2, &b);
  double sum = 0, diff = 0, diff2 = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    sum += 0.5 * (a.pixels[i] + b.pixels[i]);
    const double d = double(a.pixels[i]) - double(b.pixels[i]);
    diff += d, diff2 += d * d;
  }
  const double n = static_cast<double>(a.pixels.size());
  return {sum / n, 0.5 * (diff2 / n - (diff / n) * (diff / n))};
}

// A small full well (harsh's ICX625, 7000 e⁻, 13 e⁻ read noise): at gain 1 one grey
// level is 27.5 e⁻, so mean μ grey levels carry 27.5 μ e⁻ of shot noise and the
// variance in grey levels is μ / 27.5 + (13 / 27.5)² + 1/12 (rounding to 8 bits).
TEST(ImageSensorTest, VarianceAgainstMeanFollowsShotAndReadNoise) {
  const PhotometricOptions o = Sensor(7000.0, 13.0);
  const ImageSensor sensor(o, 320, 240, 3, 0);
  const double k = sensor.electrons_per_grey();
  EXPECT_NEAR(k, 7000.0 / 255.0, 1e-9);
  std::vector<double> means, variances;
  for (int grey : {8, 32, 64, 128, 192, 240}) {
    const Moments m = FrameMoments(sensor, grey, 1.0);
    const double expected = m.mean / k + std::pow(13.0 / k, 2) + 1.0 / 12.0;
    std::printf("grey %3d: mean %7.2f, variance %.3f (shot + read + rounding: %.3f)\n", grey,
                m.mean, m.variance, expected);
    EXPECT_NEAR(m.mean, grey, 0.1);
    EXPECT_NEAR(m.variance, expected, 0.08 * expected);
    means.push_back(m.mean);
    variances.push_back(m.variance);
  }
  // The photon-transfer slope: one grey level per k electrons.
  const double slope = (variances.back() - variances.front()) / (means.back() - means.front());
  std::printf("photon-transfer slope %.4f grey levels per grey level (1/k = %.4f)\n", slope, 1 / k);
  EXPECT_NEAR(slope, 1.0 / k, 0.05 / k);
  // Twice the gain: the same light, twice the grey levels and four times the variance.
  PhotometricOptions doubled = o;
  doubled.gain = 2.0;
  const Moments d = FrameMoments(ImageSensor(doubled, 320, 240, 3, 0), 64, 1.0);
  const Moments s = FrameMoments(sensor, 64, 1.0);
  EXPECT_NEAR(d.mean, 2 * s.mean, 0.2);
  EXPECT_NEAR(d.variance, 4 * (s.variance - 1.0 / 12) + 1.0 / 12, 0.1 * d.variance);
}

// Vignetting: a flat field comes out `corner` times as bright at the corners as at the
// centre; PRNU is a pattern fixed per camera (the same in every frame); frames repeat
// from (seed, frame) and differ between frames.
TEST(ImageSensorTest, VignettingAndFixedPatternAndReproducibleFrames) {
  PhotometricOptions o = Sensor(32691.0, 6.83);
  o.vignetting_corner = 0.5;
  o.prnu_std = 0.02;
  const ImageSensor sensor(o, 320, 240, 3, 0);
  GrayImage a = Flat(200), b = Flat(200);
  sensor.Apply(1.0, 7, 1, &a);
  sensor.Apply(1.0, 7, 1, &b);
  EXPECT_EQ(a.pixels, b.pixels);
  const auto mean_at = [&](const GrayImage& g, int u0, int v0) {
    double s = 0;
    for (int v = v0; v < v0 + 4; ++v) {
      for (int u = u0; u < u0 + 4; ++u) s += g.at(u, v);
    }
    return s / 16;
  };
  const double centre = mean_at(a, 158, 118), corner = mean_at(a, 0, 0);
  std::printf("flat field 200: centre %.1f, corner %.1f\n", centre, corner);
  EXPECT_NEAR(centre, 200.0, 4.0);
  EXPECT_NEAR(corner / centre, 0.5, 0.03);
  // The same pattern in two frames: in the centre, one frame's spread holds the 2 %
  // PRNU (4 grey levels) and the temporal noise; their difference, the noise alone.
  GrayImage c = Flat(200);
  sensor.Apply(1.0, 7, 2, &c);
  double s1 = 0, s2 = 0, d1 = 0, d2 = 0;
  int n = 0;
  for (int v = 100; v < 140; ++v) {
    for (int u = 140; u < 180; ++u, ++n) {
      const double x = a.at(u, v), d = x - c.at(u, v);
      s1 += x, s2 += x * x, d1 += d, d2 += d * d;
    }
  }
  const double spread = std::sqrt(s2 / n - (s1 / n) * (s1 / n));
  const double temporal = std::sqrt(0.5 * (d2 / n - (d1 / n) * (d1 / n)));
  std::printf("centre: spread %.2f grey levels in a frame, %.2f between frames\n", spread,
              temporal);
  EXPECT_GT(spread, 3.0 * temporal);
  const ImageSensor other(o, 320, 240, 3, 1);  // the other camera's pattern
  GrayImage d = Flat(200);
  other.Apply(1.0, 7, 1, &d);
  EXPECT_NE(a.pixels, d.pixels);
}

// A render exposed before its 8 bits clipped (scene lighting): 255 stands for light at
// or above the full well, so the pixel reads full however dark the lens's corner; a
// render exposed after (255 is the light itself) is vignetted and noisy as any other.
TEST(ImageSensorTest, AClippedRenderReadsAsAFullWell) {
  PhotometricOptions o = Sensor(32691.0, 6.83);  // typical's IMX174
  o.vignetting_corner = 0.71;
  const ImageSensor sensor(o, 320, 240, 3, 0);
  GrayImage clipped = Flat(255), exact = Flat(255);
  sensor.Apply(1.0, 7, 1, &clipped, 1.0, /*clipped_render=*/true);
  sensor.Apply(1.0, 7, 1, &exact, 1.0, /*clipped_render=*/false);
  int full = 0;
  for (std::uint8_t p : clipped.pixels) full += p == 255;
  EXPECT_EQ(full, static_cast<int>(clipped.pixels.size()));
  EXPECT_NEAR(exact.pixels[0], 255 * 0.71, 3.0);  // a corner: 181 grey levels
  EXPECT_LT(exact.pixels[120 * 320 + 160], 255 + 1);
  // Below the clip the flag changes nothing.
  GrayImage a = Flat(200), b = Flat(200);
  sensor.Apply(1.0, 7, 1, &a, 1.0, true);
  sensor.Apply(1.0, 7, 1, &b, 1.0, false);
  EXPECT_EQ(a.pixels, b.pixels);
}

// The sensor written pixel by pixel from its description in image_sensor.h and .cpp:
// the fixed pattern drawn per pixel in raster order (PRNU, then DSNU) from the camera's
// generator, the noise one of 65536 standard normals picked by the 16-bit quarters of
// a xorshift64* stream keyed by (seed, frame, camera), rounding ties to even.
void Reference(const PhotometricOptions& o, std::uint64_t pattern_seed, int camera, double exposure,
               std::uint64_t seed, std::uint64_t frame, double gain, bool clipped_render,
               GrayImage* image) {
  std::vector<float> normals(1 << 16);
  random::Generator table(0x5e4503ULL);
  for (float& v : normals) v = static_cast<float>(table.Gaussian());
  random::Generator g(
      split_mix::Mix(pattern_seed ^ (0xf1c3d0ULL + static_cast<std::uint64_t>(camera))));
  const double cx = 0.5 * (image->width - 1), cy = 0.5 * (image->height - 1);
  const float full_well = static_cast<float>(*o.full_well_e);
  const float signal_per_grey = static_cast<float>(exposure / 255.0) * full_well;
  const float read2 = static_cast<float>(*o.read_noise_e * *o.read_noise_e);
  const float dn_max = static_cast<float>((1 << *o.adc_bits) - 1);
  const float dn_per_e = static_cast<float>(*o.gain * gain) * dn_max / full_well;
  const float grey_per_dn = 255.0f / dn_max;
  std::uint64_t x =
      split_mix::Mix(seed ^ split_mix::Mix(frame * 2 + static_cast<std::uint64_t>(camera))) | 1;
  std::uint64_t bits = 0;
  for (int v = 0; v < image->height; ++v) {
    for (int u = 0; u < image->width; ++u) {
      const double r2 = ((u - cx) * (u - cx) + (v - cy) * (v - cy)) / (cx * cx + cy * cy);
      const double prnu = g.Gaussian(), dsnu = g.Gaussian();
      const float gain_px = static_cast<float>((1.0 + (*o.vignetting_corner - 1.0) * r2) *
                                               (1.0 + *o.prnu_std * prnu));
      const float offset_px = static_cast<float>(*o.dsnu_std_e * dsnu);
      const std::size_t i = static_cast<std::size_t>(v) * image->width + u;
      if (i % 4 == 0) {
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        bits = x * 0x2545f4914f6cdd1dULL;
      }
      const float n = normals[bits & 0xffff];
      bits >>= 16;
      std::uint8_t& p = image->pixels[i];
      const float signal = signal_per_grey * static_cast<float>(p) * gain_px;
      const float sigma = std::sqrt(std::max(signal, 0.0f) + read2);
      const float charge = clipped_render && p == 255 ? full_well : signal + offset_px + sigma * n;
      const float dn = std::nearbyint(std::min(std::max(charge * dn_per_e, 0.0f), dn_max));
      p = static_cast<std::uint8_t>(std::nearbyint(dn * grey_per_dn));
    }
  }
}

// Every byte as the description gives it, over sizes that leave partial blocks and
// draws, the fixed pattern on, gains, exposures and a clipped render.
TEST(ImageSensorTest, GivesTheBytesOfItsDescription) {
  PhotometricOptions o = Sensor(32691.0, 6.83);
  o.vignetting_corner = 0.71;
  o.prnu_std = 0.01;
  o.dsnu_std_e = 12.0;
  const struct {
    int width, height, camera;
    double exposure, gain;
    bool clipped;
    std::uint64_t frame;
  } cases[] = {{640, 480, 0, 1.0, 1.0, false, 3}, {640, 480, 1, 0.8, 2.5, true, 4},
               {37, 23, 0, 1.7, 1.0, false, 11},  {61, 5, 1, 0.3, 4.0, true, 0},
               {3, 1, 0, 1.0, 1.0, false, 9},     {129, 67, 1, 2.0, 1.0, true, 12}};
  for (const auto& c : cases) {
    for (const int bits : {8, 12, 16}) {
      o.adc_bits = bits;
      const ImageSensor sensor(o, c.width, c.height, 5, c.camera);
      GrayImage a;
      a.width = c.width;
      a.height = c.height;
      a.pixels.resize(static_cast<std::size_t>(c.width) * c.height);
      for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        a.pixels[i] = static_cast<std::uint8_t>(i % 7 == 0 ? 255 : (i * 37 + i / 5) % 256);
      }
      GrayImage b = a;
      sensor.Apply(c.exposure, 9, c.frame, &a, c.gain, c.clipped);
      Reference(o, 5, c.camera, c.exposure, 9, c.frame, c.gain, c.clipped, &b);
      EXPECT_EQ(a.pixels, b.pixels) << c.width << " x " << c.height << ", " << bits << " bits";
    }
  }
}

TEST(ImageSensorTest, BadOptionsNameTheirKey) {
  PhotometricOptions o = Sensor(7000.0, 13.0);
  o.adc_bits = 20;
  try {
    ImageSensor(o, 32, 32, 1, 0);
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "photometric.adc_bits");
  }
  o = Sensor(-1.0, 13.0);
  EXPECT_THROW(ImageSensor(o, 32, 32, 1, 0), OptionError);
}

}  // namespace
}  // namespace trackbed::robot
