// cv::remap's bicubic interpolation through a fixed map (see bicubic_remap.h).
#include "trackbed/perception/bicubic_remap.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace trackbed::perception {
namespace {

constexpr int kTabSize = 32;          // OpenCV's INTER_TAB_SIZE: fractions of 1/32 px
constexpr int kCoefficientBits = 15;  // INTER_REMAP_COEF_BITS
constexpr int kOne = 1 << kCoefficientBits;

// OpenCV's interpolateCubic (Keys's kernel, a = −0.75), in its float arithmetic.
void CubicCoefficients(float x, float* c) {
  const float A = -0.75f;
  c[0] = ((A * (x + 1) - 5 * A) * (x + 1) + 8 * A) * (x + 1) - 4 * A;
  c[1] = ((A + 2) * x - (A + 3)) * x * x + 1;
  c[2] = ((A + 2) * (1 - x) - (A + 3)) * (1 - x) * (1 - x) + 1;
  c[3] = 1.f - c[0] - c[1] - c[2];
}

// saturate_cast<short>(float): rounded to nearest, ties to even, then clamped.
std::int16_t SaturateShort(float v) {
  const long r = std::lrint(v);
  return static_cast<std::int16_t>(std::clamp<long>(r, -32768, 32767));
}

// initInterTab2D(INTER_CUBIC, fixpt = true): the products of the 1-D weights in fixed
// point; where they do not sum to 2^15, the largest (if short) or smallest (if over)
// of the four taps at (2..3, 2..3) takes up the difference.
std::vector<std::int16_t> BuildWeights() {
  float one_d[kTabSize][4];
  const float scale = 1.f / kTabSize;
  for (int i = 0; i < kTabSize; ++i) CubicCoefficients(static_cast<float>(i) * scale, one_d[i]);
  std::vector<std::int16_t> table(static_cast<std::size_t>(kTabSize * kTabSize * 16));
  for (int i = 0; i < kTabSize; ++i) {
    for (int j = 0; j < kTabSize; ++j) {
      std::int16_t* w = &table[static_cast<std::size_t>((i * kTabSize + j) * 16)];
      int sum = 0;
      for (int k1 = 0; k1 < 4; ++k1) {
        for (int k2 = 0; k2 < 4; ++k2) {
          w[k1 * 4 + k2] = SaturateShort(one_d[i][k1] * one_d[j][k2] * static_cast<float>(kOne));
          sum += w[k1 * 4 + k2];
        }
      }
      if (sum == kOne) continue;
      const int diff = sum - kOne;
      int max1 = 2, max2 = 2, min1 = 2, min2 = 2;
      for (int k1 = 2; k1 < 4; ++k1) {
        for (int k2 = 2; k2 < 4; ++k2) {
          if (w[k1 * 4 + k2] < w[min1 * 4 + min2]) {
            min1 = k1, min2 = k2;
          } else if (w[k1 * 4 + k2] > w[max1 * 4 + max2]) {
            max1 = k1, max2 = k2;
          }
        }
      }
      std::int16_t& adjusted = diff < 0 ? w[max1 * 4 + max2] : w[min1 * 4 + min2];
      adjusted = static_cast<std::int16_t>(adjusted - diff);
    }
  }
  return table;
}

// FixedPtCast<int, uchar, 15>: rounded, shifted back, saturated to 8 bits.
std::uint8_t FromFixedPoint(int sum) {
  return static_cast<std::uint8_t>(
      std::clamp((sum + (1 << (kCoefficientBits - 1))) >> kCoefficientBits, 0, 255));
}

#if defined(__SSE2__)
// The 16 products of one pixel's taps (rows of 4 bytes `step` apart from `s`) and
// weights `w`, as four partial sums.
inline __m128i PartialSums(const std::uint8_t* s, std::ptrdiff_t step, const std::int16_t* w) {
  std::int32_t r[4];
  for (int k = 0; k < 4; ++k) std::memcpy(&r[k], s + k * step, 4);
  const __m128i rows = _mm_set_epi32(r[3], r[2], r[1], r[0]);
  const __m128i zero = _mm_setzero_si128();
  const __m128i top = _mm_unpacklo_epi8(rows, zero);     // rows 0 and 1, 16 bits each
  const __m128i bottom = _mm_unpackhi_epi8(rows, zero);  // rows 2 and 3
  const __m128i w_top = _mm_loadu_si128(reinterpret_cast<const __m128i*>(w));
  const __m128i w_bottom = _mm_loadu_si128(reinterpret_cast<const __m128i*>(w + 8));
  return _mm_add_epi32(_mm_madd_epi16(top, w_top), _mm_madd_epi16(bottom, w_bottom));
}
#endif

}  // namespace

const std::vector<std::int16_t>& BicubicRemap::Weights() {
  static const std::vector<std::int16_t> table = BuildWeights();
  return table;
}

BicubicRemap::BicubicRemap(const cv::Mat& map_xy, const cv::Mat& map_a, cv::Size source_size)
    : source_size_(source_size), size_(map_xy.size()) {
  if (map_xy.type() != CV_16SC2 || map_a.type() != CV_16UC1 || map_a.size() != map_xy.size() ||
      source_size.width < 1 || source_size.height < 1) {
    throw std::invalid_argument(
        "BicubicRemap: needs CV_16SC2 and CV_16UC1 maps of one size and a source size");
  }
  const std::size_t n = static_cast<std::size_t>(size_.area());
  offset_.assign(n, 0);
  entry_.resize(n);
  inside_.resize(n);
  // cv::remap's test for the fast path: column in [0, width − 4], row in [0, height − 4].
  const auto last_column = static_cast<unsigned>(std::max(source_size.width - 3, 0));
  const auto last_row = static_cast<unsigned>(std::max(source_size.height - 3, 0));
  for (int y = 0; y < size_.height; ++y) {
    const std::int16_t* xy = map_xy.ptr<std::int16_t>(y);
    const std::uint16_t* a = map_a.ptr<std::uint16_t>(y);
    for (int x = 0; x < size_.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * size_.width + x;
      const int column = xy[2 * x] - 1, row = xy[2 * x + 1] - 1;
      entry_[i] = static_cast<std::uint16_t>(a[x] & (kTabSize * kTabSize - 1));
      inside_[i] =
          static_cast<unsigned>(column) < last_column && static_cast<unsigned>(row) < last_row;
      if (inside_[i]) {
        offset_[i] = row * source_size.width + column;
      } else {
        border_.push_back({static_cast<std::int32_t>(i), column, row, entry_[i]});
      }
    }
  }
}

void BicubicRemap::Apply(const cv::Mat& source, cv::Mat* out) const {
  if (source.type() != CV_8UC1 || source.size() != source_size_) {
    throw std::invalid_argument("BicubicRemap::Apply: needs a CV_8UC1 image of the map's source");
  }
  cv::Mat src = source.isContinuous() ? source : source.clone();
  out->create(size_, CV_8UC1);
  std::uint8_t* dst = out->ptr<std::uint8_t>();
  const std::uint8_t* s = src.ptr<std::uint8_t>();
  const std::ptrdiff_t step = source_size_.width;
  const std::int16_t* weights = Weights().data();
  const std::size_t n = offset_.size();
  // One pixel whose taps all lie inside: one integer sum.
  const auto inside_pixel = [&](std::size_t k) {
    const std::uint8_t* t = s + offset_[k];
    const std::int16_t* w = weights + 16 * entry_[k];
    int sum = 0;
    for (int r = 0; r < 4; ++r, t += step, w += 4) {
      sum += t[0] * w[0] + t[1] * w[1] + t[2] * w[2] + t[3] * w[3];
    }
    dst[k] = FromFixedPoint(sum);
  };
  std::size_t i = 0;
#if defined(__SSE2__)
  // Four pixels at a time: where all their taps lie inside, their partial sums
  // transposed and added, then rounded, shifted and saturated together.
  const __m128i half = _mm_set1_epi32(1 << (kCoefficientBits - 1));
  for (; i + 4 <= n; i += 4) {
    std::uint32_t all_inside;
    std::memcpy(&all_inside, &inside_[i], 4);
    if (all_inside != 0x01010101u) {
      for (std::size_t k = i; k < i + 4; ++k) {
        if (inside_[k]) inside_pixel(k);
      }
      continue;
    }
    __m128i p[4];
    for (int k = 0; k < 4; ++k) {
      p[k] = PartialSums(s + offset_[i + k], step, weights + 16 * entry_[i + k]);
    }
    const __m128i a01 =
        _mm_add_epi32(_mm_unpacklo_epi32(p[0], p[1]), _mm_unpackhi_epi32(p[0], p[1]));
    const __m128i a23 =
        _mm_add_epi32(_mm_unpacklo_epi32(p[2], p[3]), _mm_unpackhi_epi32(p[2], p[3]));
    const __m128i sums = _mm_add_epi32(_mm_unpacklo_epi64(a01, a23), _mm_unpackhi_epi64(a01, a23));
    const __m128i shifted = _mm_srai_epi32(_mm_add_epi32(sums, half), kCoefficientBits);
    const __m128i bytes = _mm_packus_epi16(_mm_packs_epi32(shifted, shifted), shifted);
    const std::int32_t four = _mm_cvtsi128_si32(bytes);
    std::memcpy(dst + i, &four, 4);
  }
#endif
  for (; i < n; ++i) {
    if (inside_[i]) inside_pixel(i);
  }
  // Taps outside the source are black: they add nothing to the sum.
  for (const Border& b : border_) {
    const std::int16_t* w = weights + 16 * b.entry;
    int sum = 0;
    for (int r = 0; r < 4; ++r) {
      const int row = b.row + r;
      if (row < 0 || row >= source_size_.height) continue;
      for (int c = 0; c < 4; ++c) {
        const int column = b.column + c;
        if (column < 0 || column >= source_size_.width) continue;
        sum += s[static_cast<std::ptrdiff_t>(row) * step + column] * w[r * 4 + c];
      }
    }
    dst[b.pixel] = FromFixedPoint(sum);
  }
}

}  // namespace trackbed::perception
