// Building blocks of the procedural textures (procedural_texture.cpp and the ground
// recipes in ground_*.cpp): seeded randomness, small math, square fields over one
// tile, periodic gradient and cellular noise, and relief shading. Private to the
// renderer. Bit-exactness across machines: randomness comes from an integer hash and
// SplitMix64 only; floating point uses + − × ÷ sqrt floor, never libm's transcendental
// functions; and no expression draws from a generator twice. A file including this
// header turns off floating-point contraction before it (see procedural_texture.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "trackbed/common/split_mix.h"

namespace trackbed::render::texture_blocks {

// ---------------------------------------------------------------------------
// Randomness.

// SplitMix64 (common/split_mix.h): its increment, its output function as the mixer,
// and its independent sub-seeds (stream `k` of `seed`).
using split_mix::kGamma;
using split_mix::Stream;
constexpr std::uint64_t Mix(std::uint64_t z) { return split_mix::Finalize(z); }

// Hash of the integer point (i, j) in stream `seed`.
inline std::uint64_t HashPoint(std::uint64_t seed, int i, int j) {
  const std::uint64_t packed = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) |
                               static_cast<std::uint32_t>(j);
  return Mix(seed ^ Mix(packed + kGamma));
}

// A uniform double in [0, 1) from the top 53 bits of `h`.
inline double UnitFromBits(std::uint64_t h) {
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

// An approximately standard normal number from `h`: the Irwin–Hall sum of four
// uniforms, scaled to unit variance (so bounded by ±2√3, which textures prefer).
inline double GaussFromBits(std::uint64_t h) {
  const double sum = static_cast<double>(h & 0xffff) + static_cast<double>((h >> 16) & 0xffff) +
                     static_cast<double>((h >> 32) & 0xffff) + static_cast<double>(h >> 48);
  constexpr double kSqrt3 = 1.7320508075688772;
  return (sum / 65536.0 - 2.0) * kSqrt3;
}

// SplitMix64 as a sequential generator for placing shapes.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t Next() { return Mix(state_ += kGamma); }
  double Uniform() { return UnitFromBits(Next()); }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  double Gauss() { return GaussFromBits(Next()); }
  bool Chance(double p) { return Uniform() < p; }
  /// A uniformly distributed unit vector, by rejection from the square (no trigonometry).
  Eigen::Vector2d Direction() {
    for (;;) {
      const double x = Uniform(-1.0, 1.0);
      const double y = Uniform(-1.0, 1.0);
      const double r2 = x * x + y * y;
      if (r2 > 1e-4 && r2 <= 1.0) return Eigen::Vector2d(x, y) / std::sqrt(r2);
    }
  }

 private:
  std::uint64_t state_;
};

// FNV-1a of a name, so each appearance draws from its own streams.
inline std::uint64_t HashName(const std::string& name) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

// ---------------------------------------------------------------------------
// Small math.

inline double Clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }
inline double Lerp(double a, double b, double t) { return a + (b - a) * t; }
inline double SmoothStep(double e0, double e1, double x) {
  const double t = Clamp01((x - e0) / (e1 - e0));
  return t * t * (3.0 - 2.0 * t);
}
// Perlin's (2002) quintic fade: C2-continuous interpolation weight.
inline double Fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
// A smooth wave of period 1 close to cos(2πt) (smoothstep of a triangle wave), used
// instead of std::cos so that bytes do not depend on libm.
inline double Wave(double t) {
  const double tri = std::abs(2.0 * (t - std::floor(t)) - 1.0);
  return 2.0 * tri * tri * (3.0 - 2.0 * tri) - 1.0;
}
// Distance from x to the nearest multiple of `pitch` (both in the same unit).
inline double DistanceToGrid(double x, double pitch) {
  const double r = x / pitch;
  return std::abs(r - std::floor(r + 0.5)) * pitch;
}
// Antialiased coverage of a texel whose centre is `signed_distance_px` outside a shape
// (negative inside): a one-texel-wide linear ramp.
inline double Coverage(double signed_distance_px) { return Clamp01(0.5 - signed_distance_px); }
inline int WrapIndex(int i, int period) {
  if (i >= 0 && i < period) return i;  // the common case, without a division
  return ((i % period) + period) % period;
}
// floor() for |x| < 2³¹ without a libm call (hot in the noise functions).
inline int FloorInt(double x) {
  const int i = static_cast<int>(x);
  return x < i ? i - 1 : i;
}

// ---------------------------------------------------------------------------
// Fields and periodic noise.

// A square scalar field over one tile: grey levels, or heights before shading.
struct Field {
  explicit Field(int size, double fill = 0.0)
      : n(size), v(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), fill) {}
  double& at(int x, int y) { return v[Index(x, y)]; }
  double at(int x, int y) const { return v[Index(x, y)]; }
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>((y & (n - 1)) * n + (x & (n - 1)));
  }
  int n;
  std::vector<double> v;
};

// Calls fn(x, y, u, v, value&) for every texel, with (u, v) its centre in tile units.
template <typename F>
inline void ForEachTexel(Field& f, F&& fn) {
  const double inv = 1.0 / f.n;
  for (int y = 0; y < f.n; ++y) {
    for (int x = 0; x < f.n; ++x) {
      fn(x, y, (x + 0.5) * inv, (y + 0.5) * inv, f.v[static_cast<std::size_t>(y * f.n + x)]);
    }
  }
}

// Calls fn(value&, dx, dy, x, y) for every texel whose centre lies in the box of half
// sides rx × ry [px] around the point (cx, cy) [px], with (dx, dy) the centre's offset
// from that point [px]. Indices wrap, so a shape crossing an edge continues on the other
// side. A box wider than the tile visits each texel once.
template <typename F>
inline void ForEachInBox(Field& f, double cx, double cy, double rx, double ry, F&& fn) {
  const int x0 = static_cast<int>(std::floor(cx - rx - 0.5));
  const int x1 = std::min(static_cast<int>(std::floor(cx + rx - 0.5)) + 1, x0 + f.n - 1);
  const int y0 = static_cast<int>(std::floor(cy - ry - 0.5));
  const int y1 = std::min(static_cast<int>(std::floor(cy + ry - 0.5)) + 1, y0 + f.n - 1);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      fn(f.at(x, y), x + 0.5 - cx, y + 0.5 - cy, x, y);
    }
  }
}

// ForEachInBox over the square of half side `radius_px`.
template <typename F>
inline void ForEachNear(Field& f, double cx, double cy, double radius_px, F&& fn) {
  ForEachInBox(f, cx, cy, radius_px, radius_px, std::forward<F>(fn));
}

// Half extents [px] of the bounding box of an ellipse with semi-axes a along the unit
// vector d and b across it.
inline Eigen::Vector2d EllipseExtent(double a, double b, const Eigen::Vector2d& d) {
  return Eigen::Vector2d(std::sqrt(a * a * d.x() * d.x() + b * b * d.y() * d.y()),
                         std::sqrt(a * a * d.y() * d.y() + b * b * d.x() * d.x()));
}

// Sets the field's mean and standard deviation (an affine map; a constant field only
// gets the mean).
inline void SetMeanStd(Field& f, double mean, double sd) {
  double sum = 0.0;
  for (const double x : f.v) sum += x;
  const double m = sum / static_cast<double>(f.v.size());
  double ss = 0.0;
  for (const double x : f.v) ss += (x - m) * (x - m);
  const double s = std::sqrt(ss / static_cast<double>(f.v.size()));
  const double k = s > 0.0 ? sd / s : 0.0;
  for (double& x : f.v) x = mean + (x - m) * k;
}

// Periodic 2-D gradient noise (Perlin 2002) with period_x × period_y lattice cells
// across the tile; roughly in [-0.7, 0.7]. Gradients come from 16 fixed directions.
// The lattice is shifted by a random fraction of a cell, so that the octaves of an Fbm
// do not all share grid lines (at u = 0 in particular, where they would mark the
// tile's edge).
class GradientNoise {
 public:
  GradientNoise(std::uint64_t seed, int period_x, int period_y)
      : px_(period_x),
        py_(period_y),
        shift_x_(UnitFromBits(HashPoint(seed, -1, 0))),
        shift_y_(UnitFromBits(HashPoint(seed, 0, -1))),
        grad_(2 * static_cast<std::size_t>(period_x * period_y)) {
    // cos and sin of k·22.5°, k = 0…15, as constants.
    static constexpr double kCos[16] = {
        1.0,  0.9238795325112867,  0.7071067811865476,  0.3826834323650898,
        0.0,  -0.3826834323650898, -0.7071067811865476, -0.9238795325112867,
        -1.0, -0.9238795325112867, -0.7071067811865476, -0.3826834323650898,
        0.0,  0.3826834323650898,  0.7071067811865476,  0.9238795325112867};
    for (int j = 0; j < py_; ++j) {
      for (int i = 0; i < px_; ++i) {
        const int k = static_cast<int>(HashPoint(seed, i, j) & 15);
        const std::size_t at = 2 * static_cast<std::size_t>(j * px_ + i);
        grad_[at] = kCos[k];
        grad_[at + 1] = kCos[(k + 12) & 15];  // sin θ = cos(θ − 90°)
      }
    }
  }

  double operator()(double u, double v) const {
    const double x = u * px_ + shift_x_;
    const double y = v * py_ + shift_y_;
    const int xi = FloorInt(x);
    const int yi = FloorInt(y);
    const double fx = x - xi;
    const double fy = y - yi;
    const int i0 = WrapIndex(xi, px_);
    const int j0 = WrapIndex(yi, py_);
    const int i1 = i0 + 1 == px_ ? 0 : i0 + 1;
    const int j1 = j0 + 1 == py_ ? 0 : j0 + 1;
    const double* row0 = &grad_[2 * static_cast<std::size_t>(j0 * px_)];
    const double* row1 = &grad_[2 * static_cast<std::size_t>(j1 * px_)];
    const double n00 = row0[2 * i0] * fx + row0[2 * i0 + 1] * fy;
    const double n10 = row0[2 * i1] * (fx - 1.0) + row0[2 * i1 + 1] * fy;
    const double n01 = row1[2 * i0] * fx + row1[2 * i0 + 1] * (fy - 1.0);
    const double n11 = row1[2 * i1] * (fx - 1.0) + row1[2 * i1 + 1] * (fy - 1.0);
    const double s = Fade(fx);
    return Lerp(Lerp(n00, n10, s), Lerp(n01, n11, s), Fade(fy));
  }

 private:
  int px_;
  int py_;
  double shift_x_;  // lattice offset [cells]
  double shift_y_;
  std::vector<double> grad_;  // (x, y) of each lattice point's gradient, row-major
};

// Fractional Brownian motion: up to `octaves` layers of GradientNoise, each with twice
// the lattice frequency and `gain` times the amplitude of the one before. Layers finer
// than a texel of a `size_px` texture are left out.
class Fbm {
 public:
  Fbm(std::uint64_t seed, int period_x, int period_y, int octaves, double gain, int size_px) {
    double amplitude = 1.0;
    for (int k = 0; k < octaves; ++k) {
      const int px = period_x << k;
      const int py = period_y << k;
      if (k > 0 && std::max(px, py) > size_px) break;
      layers_.emplace_back(Stream(seed, static_cast<std::uint64_t>(k)), px, py);
      amplitudes_.push_back(amplitude);
      amplitude *= gain;
    }
  }
  double operator()(double u, double v) const {
    double sum = 0.0;
    for (std::size_t k = 0; k < layers_.size(); ++k) sum += amplitudes_[k] * layers_[k](u, v);
    return sum;
  }

 private:
  std::vector<GradientNoise> layers_;
  std::vector<double> amplitudes_;
};

// A field of `noise` standardised to zero mean and unit deviation.
template <typename Noise>
inline Field NoiseField(int n, const Noise& noise) {
  Field f(n);
  ForEachTexel(f, [&](int, int, double u, double v, double& value) { value = noise(u, v); });
  SetMeanStd(f, 0.0, 1.0);
  return f;
}

// Periodic cellular noise (Worley 1996): one jittered feature point per cell of a
// cells_x × cells_y lattice over the tile. Cells are assigned by distance in lattice
// units (so a lattice with cells_y < cells_x gives tall cells); border distances are
// measured in tile units.
class Cells {
 public:
  struct Sample {
    double edge = 0.0;  ///< Distance to the nearest cell border [tile units].
    int id = 0;         ///< The nearest point's cell, for per-cell properties.
    /// From the sample to the nearest point [lattice units].
    Eigen::Vector2d to_point = Eigen::Vector2d::Zero();
  };

  Cells(std::uint64_t seed, int cells_x, int cells_y, double jitter)
      : cx_(cells_x),
        cy_(cells_y),
        cmax_(std::max(cells_x, cells_y)),
        shift_x_(UnitFromBits(HashPoint(seed, -1, 0))),
        shift_y_(UnitFromBits(HashPoint(seed, 0, -1))) {
    for (int j = 0; j < cy_; ++j) {
      for (int i = 0; i < cx_; ++i) {
        const std::uint64_t h = HashPoint(seed, i, j);
        px_.push_back(0.5 + jitter * (UnitFromBits(h) - 0.5));
        py_.push_back(0.5 + jitter * (UnitFromBits(Mix(h)) - 0.5));
      }
    }
  }

  // The nearest point among the 3×3 cells around the sample, then the closest
  // bisector among the 5×5 (Quílez, "Voronoi edges", 2012); exact near borders, which
  // is where the distance matters. Borders farther than `max_edge` [tile] report
  // `max_edge`, which lets most of the 5×5 be skipped.
  Sample operator()(double u, double v, double max_edge = 1e300) const {
    const double x = u * cx_ + shift_x_;
    const double y = v * cy_ + shift_y_;
    const int ix = FloorInt(x);
    const int iy = FloorInt(y);
    int cols[5];
    int rows[5];
    for (int k = 0; k < 5; ++k) {
      cols[k] = WrapIndex(ix + k - 2, cx_);
      rows[k] = WrapIndex(iy + k - 2, cy_);
    }
    // Offsets from the sample to the points of the 5×5 window, inner 3×3 first: their
    // bisectors are usually the nearest, and prune the outer ring.
    static constexpr int kOrder[25][2] = {{2, 2}, {1, 2}, {3, 2}, {2, 1}, {2, 3}, {1, 1}, {3, 1},
                                          {1, 3}, {3, 3}, {0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0},
                                          {0, 1}, {4, 1}, {0, 2}, {4, 2}, {0, 3}, {4, 3}, {0, 4},
                                          {1, 4}, {2, 4}, {3, 4}, {4, 4}};
    double rx[25];
    double ry[25];
    double r2[25];
    auto compute = [&](int k) {
      const int a = kOrder[k][0];
      const int b = kOrder[k][1];
      const std::size_t id = static_cast<std::size_t>(rows[b] * cx_ + cols[a]);
      rx[k] = ix + a - 2 + px_[id] - x;
      ry[k] = iy + b - 2 + py_[id] - y;
      r2[k] = rx[k] * rx[k] + ry[k] * ry[k];
    };
    int nearest = 0;
    for (int k = 0; k < 9; ++k) {
      compute(k);
      if (r2[k] < r2[nearest]) nearest = k;
    }
    Sample s;
    s.id = rows[kOrder[nearest][1]] * cx_ + cols[kOrder[nearest][0]];
    s.to_point = Eigen::Vector2d(rx[nearest], ry[nearest]);
    const double best = r2[nearest];
    const double f1 = std::sqrt(best);
    double edge = max_edge;
    for (int k = 0; k < 25; ++k) {
      if (k >= 9) {
        // Points of the outer ring are at least one lattice unit away: done if that
        // cannot beat the border found so far.
        if (k == 9 && f1 + 2.0 * cmax_ * edge <= 1.0) break;
        compute(k);
      }
      // The border with point k lies at least (|r| − f1)/2 lattice units away, i.e. at
      // least that over cmax in tile units: skip points that cannot beat `edge`.
      const double reach = f1 + 2.0 * cmax_ * edge;
      if (r2[k] <= best || r2[k] >= reach * reach) continue;
      const double bx = (rx[k] - rx[nearest]) * cx_;
      const double by = (ry[k] - ry[nearest]) * cy_;
      edge = std::min(edge, 0.5 * (r2[k] - best) / std::sqrt(bx * bx + by * by));
    }
    s.edge = edge;
    return s;
  }

 private:
  int cx_;
  int cy_;
  int cmax_;
  double shift_x_;  // lattice offset [cells], as for GradientNoise
  double shift_y_;
  std::vector<double> px_;  // feature points within their cells, [0, 1)
  std::vector<double> py_;
};

// cos of the angle between a surface normal n and the direction l to the light (neither
// need be unit), written out in scalars so that no vectorised reduction can change the
// order of the sums.
inline double Lambert(double nx, double ny, double nz, double lx, double ly, double lz) {
  return (nx * lx + ny * ly + nz * lz) /
         std::sqrt((nx * nx + ny * ny + nz * nz) * (lx * lx + ly * ly + lz * lz));
}

// Relief shading of a height field (heights in tile units): n·l for a light in
// direction (lx, ly, lz) minus the flat-ground value, so 0 on level ground.
inline Field Relief(const Field& height, double lx, double ly, double lz) {
  const double flat = Lambert(0.0, 0.0, 1.0, lx, ly, lz);
  Field out(height.n);
  const double half_n = 0.5 * height.n;  // central difference per tile unit
  for (int y = 0; y < height.n; ++y) {
    for (int x = 0; x < height.n; ++x) {
      const double hx = (height.at(x + 1, y) - height.at(x - 1, y)) * half_n;
      const double hy = (height.at(x, y + 1) - height.at(x, y - 1)) * half_n;
      out.at(x, y) = Lambert(-hx, -hy, 1.0, lx, ly, lz) - flat;
    }
  }
  return out;
}

// The light all relief shading uses: from the upper left (−u, −v) and above.
constexpr double kLightX = -0.5;
constexpr double kLightY = -0.6;
constexpr double kLightZ = 0.62;

}  // namespace trackbed::render::texture_blocks
