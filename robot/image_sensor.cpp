// The image sensor in electrons (see image_sensor.h).
#include "trackbed/robot/image_sensor.h"

#include <algorithm>
#include <cmath>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "trackbed/common/option_error.h"
#include "trackbed/common/random.h"
#include "trackbed/common/split_mix.h"

namespace trackbed::robot {
namespace {

// 65536 standard normal values (Box–Muller from a fixed seed), built once: a pixel's
// noise is one of them, picked by 16 random bits.
const std::vector<float>& UnitNormals() {
  static const std::vector<float> table = [] {
    std::vector<float> t(1 << 16);
    random::Generator g(0x5e4503ULL);
    for (float& v : t) v = static_cast<float>(g.Gaussian());
    return t;
  }();
  return table;
}

// x rounded to the nearest integer, ties to even (std::nearbyint's result in the default
// rounding mode), for 0 <= x < 2^22: adding 1.5 * 2^23 leaves no fraction bits, so the
// float addition rounds x. Inline, where nearbyint is a library call per pixel; clamping
// before rounding gives the same integers, since rounding is monotone and the bounds
// (0 and the ADC's largest number, at most 65535) are integers.
inline float RoundToEven(float x) {
  constexpr float kShift = 12582912.0f;  // 1.5 * 2^23
  return (x + kShift) - kShift;
}

// v[k] = sqrt(v[k]) for k < m: SSE's square root, four at a time, where the compiler
// would call the library's per value (for errno); both are IEEE's correctly rounded one.
void SqrtBlock(float* v, std::size_t m) {
  std::size_t k = 0;
#if defined(__SSE2__)
  for (; k + 4 <= m; k += 4) _mm_storeu_ps(v + k, _mm_sqrt_ps(_mm_loadu_ps(v + k)));
#endif
  for (; k < m; ++k) v[k] = std::sqrt(v[k]);
}

}  // namespace

void PhotometricOptions::Validate() const {
  if (full_well_e) option_check::Positive("photometric.full_well_e", *full_well_e);
  if (read_noise_e) option_check::NonNegative("photometric.read_noise_e", *read_noise_e);
  if (prnu_std) option_check::InRange("photometric.prnu_std", *prnu_std, 0.0, 0.5);
  if (dsnu_std_e) option_check::NonNegative("photometric.dsnu_std_e", *dsnu_std_e);
  if (adc_bits && (*adc_bits < 8 || *adc_bits > 16)) {
    throw OptionError("photometric.adc_bits",
                      "must be in [8, 16] (got " + std::to_string(*adc_bits) + ")");
  }
  if (vignetting_corner) {
    option_check::InRange("photometric.vignetting_corner", *vignetting_corner, 1e-3, 1.0);
  }
  if (gain) option_check::InRange("photometric.gain", *gain, 1.0, 1000.0);
}

ImageSensor::ImageSensor(const PhotometricOptions& options, int width_px, int height_px,
                         std::uint64_t seed, int camera)
    : o_(options), width_(width_px), height_(height_px), camera_(camera) {
  o_.Validate();
  if (!(o_.full_well_e && o_.read_noise_e && o_.prnu_std && o_.dsnu_std_e && o_.adc_bits &&
        o_.vignetting_corner && o_.gain)) {
    throw OptionError("photometric", "every key must be resolved");
  }
  const std::size_t n = static_cast<std::size_t>(width_px) * height_px;
  gain_map_.resize(n);
  offset_map_.resize(n);
  random::Generator g(split_mix::Mix(seed ^ (0xf1c3d0ULL + static_cast<std::uint64_t>(camera))));
  const double cx = 0.5 * (width_px - 1), cy = 0.5 * (height_px - 1);
  const double half_diagonal2 = cx * cx + cy * cy;
  for (int v = 0; v < height_px; ++v) {
    for (int u = 0; u < width_px; ++u) {
      const double r2 = ((u - cx) * (u - cx) + (v - cy) * (v - cy)) / half_diagonal2;
      const double vignetting = 1.0 + (*o_.vignetting_corner - 1.0) * r2;
      const std::size_t i = static_cast<std::size_t>(v) * width_px + u;
      const double prnu = g.Gaussian(), dsnu = g.Gaussian();
      gain_map_[i] = static_cast<float>(vignetting * (1.0 + *o_.prnu_std * prnu));
      offset_map_[i] = static_cast<float>(*o_.dsnu_std_e * dsnu);
    }
  }
}

double ImageSensor::electrons_per_grey() const { return *o_.full_well_e / (*o_.gain * 255.0); }

void ImageSensor::Apply(double exposure, std::uint64_t seed, std::uint64_t frame, GrayImage* image,
                        double gain, bool clipped_render) const {
  if (image->width != width_ || image->height != height_) {
    throw std::invalid_argument("ImageSensor: the image is not the sensor's size");
  }
  const float full_well = static_cast<float>(*o_.full_well_e);
  const float signal_per_grey = static_cast<float>(exposure / 255.0) * full_well;
  const float read2 = static_cast<float>(*o_.read_noise_e * *o_.read_noise_e);
  const float dn_max = static_cast<float>((1 << *o_.adc_bits) - 1);
  const float dn_per_e = static_cast<float>(*o_.gain * gain) * dn_max / full_well;
  const float grey_per_dn = 255.0f / dn_max;
  const float* normal = UnitNormals().data();
  // A xorshift64* stream keyed by (seed, frame, camera), 16 bits per pixel indexing the
  // table (as ApplySensorModel's noise), four pixels per draw from the low quarter up.
  std::uint64_t x =
      split_mix::Mix(seed ^ split_mix::Mix(frame * 2 + static_cast<std::uint64_t>(camera_))) | 1;
  std::uint8_t* px = image->pixels.data();
  const float* gain_map = gain_map_.data();
  const float* offset_map = offset_map_.data();
  const std::size_t n = image->pixels.size();
  // Blocks of 64 pixels: their noise drawn first, then each step of the arithmetic over
  // the block, which the compiler vectorises (the square root by SqrtBlock); the bytes
  // are those of the formula pixel by pixel (build/tests/image_sensor_test).
  constexpr std::size_t kBlock = 64;
  alignas(16) float noise[kBlock], signal[kBlock], sigma[kBlock];
  for (std::size_t i0 = 0; i0 < n; i0 += kBlock) {
    const std::size_t m = std::min(kBlock, n - i0);
    for (std::size_t k = 0; k < m; k += 4) {
      x ^= x >> 12;
      x ^= x << 25;
      x ^= x >> 27;
      const std::uint64_t bits = x * 0x2545f4914f6cdd1dULL;
      for (std::size_t q = 0; q < 4; ++q) noise[k + q] = normal[(bits >> (16 * q)) & 0xffff];
    }
    std::uint8_t* p = px + i0;
    const float* gm = gain_map + i0;
    const float* om = offset_map + i0;
    for (std::size_t k = 0; k < m; ++k) {
      signal[k] = signal_per_grey * static_cast<float>(p[k]) * gm[k];
      sigma[k] = std::max(signal[k], 0.0f) + read2;
    }
    SqrtBlock(sigma, m);
    for (std::size_t k = 0; k < m; ++k) {
      const float charge =
          clipped_render && p[k] == 255 ? full_well : signal[k] + om[k] + sigma[k] * noise[k];
      const float dn = RoundToEven(std::min(std::max(charge * dn_per_e, 0.0f), dn_max));
      p[k] = static_cast<std::uint8_t>(RoundToEven(dn * grey_per_dn));
    }
  }
}

}  // namespace trackbed::robot
