// A texture's mip chain pre-filtered for long pixel footprints (see footprint_mips.h).
#include "footprint_mips.h"

#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace trackbed::render {
namespace {

struct Direction {
  double x = 1.0, y = 0.0;
};

// The unit vectors at k·π/n, k = 0 … n−1 (n a power of two ≥ 4), from half-angle
// formulas and rotations: sqrt, products and sums only.
std::vector<Direction> Directions(int n) {
  double c = std::sqrt(0.5), s = std::sqrt(0.5);  // π/4
  for (int m = 4; m < n; m *= 2) {
    const double half_c = std::sqrt(0.5 * (1.0 + c));
    s = s / (2.0 * half_c);
    c = half_c;
  }
  std::vector<Direction> out(static_cast<std::size_t>(n));
  for (std::size_t k = 1; k < out.size(); ++k) {
    out[k] = {out[k - 1].x * c - out[k - 1].y * s, out[k - 1].x * s + out[k - 1].y * c};
  }
  return out;
}

// A square level of side n, texels as doubles, wrapping around.
struct Level {
  int n = 0;
  std::vector<double> v;
  double At(int x, int y) const {
    return v[static_cast<std::size_t>((y & (n - 1)) * n + (x & (n - 1)))];
  }
  double Bilinear(double x, double y) const {
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
    return (1.0 - ay) * ((1.0 - ax) * At(ix, iy) + ax * At(ix + 1, iy)) +
           ay * ((1.0 - ax) * At(ix, iy + 1) + ax * At(ix + 1, iy + 1));
  }
};

// The mean of two copies of `in` shifted ±`shift` texels along `d`.
Level Spread(const Level& in, const Direction& d, double shift) {
  Level out{in.n, std::vector<double>(in.v.size())};
  const double dx = d.x * shift, dy = d.y * shift;
  for (int y = 0; y < in.n; ++y) {
    for (int x = 0; x < in.n; ++x) {
      out.v[static_cast<std::size_t>(y * in.n + x)] =
          0.5 * (in.Bilinear(x + dx, y + dy) + in.Bilinear(x - dx, y - dy));
    }
  }
  return out;
}

std::uint8_t Byte(double v) {
  return static_cast<std::uint8_t>(std::fmin(255.0, std::fmax(0.0, std::floor(v + 0.5))));
}

// The isotropic chain as bytes: 2 × 2 box filtering, rounded, down to 1 × 1.
std::vector<std::vector<std::uint8_t>> IsotropicChain(const Texture& t) {
  std::vector<std::vector<std::uint8_t>> chain{t.texels};
  for (int size = t.size_px; size > 1; size /= 2) {
    const std::vector<std::uint8_t>& level = chain.back();
    const int half = size / 2;
    std::vector<std::uint8_t> next(static_cast<std::size_t>(half) * half);
    const auto at = [&](int x, int y) {
      return static_cast<int>(level[static_cast<std::size_t>(y) * size + x]);
    };
    for (int y = 0; y < half; ++y) {
      for (int x = 0; x < half; ++x) {
        next[static_cast<std::size_t>(y) * half + x] =
            static_cast<std::uint8_t>((at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) +
                                       at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1) + 2) /
                                      4);
      }
    }
    chain.push_back(std::move(next));
  }
  return chain;
}

}  // namespace

FootprintMips MakeFootprintMips(const Texture& t, int directions) {
  if (directions != 0 && (directions < 4 || (directions & (directions - 1)) != 0)) {
    throw std::invalid_argument("MakeFootprintMips: directions must be 0 or a power of two >= 4");
  }
  FootprintMips out;
  out.directions = directions;
  out.layers = 1 + kMaxAnisotropyLog2 * directions;
  out.levels = IsotropicChain(t);
  if (directions == 0) return out;
  const std::vector<Direction> dirs = Directions(directions);
  for (std::vector<std::uint8_t>& bytes : out.levels) {
    Level iso{1, std::vector<double>(bytes.begin(), bytes.end())};
    while (static_cast<std::size_t>(iso.n) * iso.n < iso.v.size()) iso.n *= 2;
    const std::size_t texels = iso.v.size();
    bytes.resize(texels * static_cast<std::size_t>(out.layers));
    for (int k = 0; k < directions; ++k) {
      Level layer = iso;
      for (int m = 1; m <= kMaxAnisotropyLog2; ++m) {
        layer = Spread(layer, dirs[static_cast<std::size_t>(k)], std::ldexp(1.0, m - 2));
        std::uint8_t* dst = &bytes[texels * static_cast<std::size_t>(1 + (m - 1) * directions + k)];
        for (std::size_t i = 0; i < texels; ++i) dst[i] = Byte(layer.v[i]);
      }
    }
  }
  return out;
}

}  // namespace trackbed::render
