// trackbed-lint: long-file (procedural texture recipes, one per appearance)
// Seeded procedural textures (see procedural_texture.h), composed per appearance from a
// few periodic building blocks: gradient noise on a wrapped lattice (Perlin 2002),
// cellular noise on a wrapped lattice (Worley 1996), antialiased shapes painted with
// wrap-around, and height fields shaded by a fixed light. Every block is periodic over
// the tile, which is what makes the textures seamless under GL_REPEAT.
//
// Layout is in tile units (u, v ∈ [0, 1), u along a row, v down the columns), so a
// texture's content does not depend on its resolution; noise octaves finer than a texel
// are dropped. Bit-exactness across machines: randomness comes from an integer hash and
// SplitMix64 only; floating point uses + − × ÷ sqrt floor, never libm's transcendental
// functions; and no expression draws from a generator twice (operand order of
// evaluation is unspecified in C++).
#include "trackbed/render/procedural_texture.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <Eigen/Core>

#include "trackbed/common/split_mix.h"

// Fusing a·b + c into one FMA changes rounding, so bytes would depend on whether the
// target has FMA (ARM64 has, baseline x86-64 has not): keep every product rounded.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

// After the pragma, so that the blocks' inline functions are compiled under it too.
#include "corridor_fitting_textures.h"
#include "facade_texture.h"
#include "ground_asphalt.h"
#include "ground_grass.h"
#include "ground_sand.h"
#include "ground_soil.h"
#include "texture_blocks.h"

namespace trackbed::render {

std::uint8_t Texture::at(int x, int y) const {
  assert(size_px > 0 && (size_px & (size_px - 1)) == 0);
  // A power-of-two size wraps any integer, negative ones too, by masking.
  const int mask = size_px - 1;
  return texels[static_cast<std::size_t>((y & mask) * size_px + (x & mask))];
}

namespace {

using namespace texture_blocks;  // NOLINT: the recipes are written in its terms

// ---------------------------------------------------------------------------
// Indoor appearances: nearly featureless on purpose (few trackable corners).

// Roller-applied wall paint: broad mottling of about one grey level, nothing texel-sized.
void PlainPaint(Field& f, std::uint64_t seed) {
  f = NoiseField(f.n, Fbm(Stream(seed, 0), 3, 3, 3, 0.5, f.n));
  SetMeanStd(f, 200.0, 1.2);
}

// A plastered ceiling: brighter and even smoother than paint.
void Ceiling(Field& f, std::uint64_t seed) {
  f = NoiseField(f.n, Fbm(Stream(seed, 0), 2, 2, 3, 0.45, f.n));
  SetMeanStd(f, 225.0, 1.0);
}

// Brushed sheet metal: faint streaks along u over a broad sheen.
void Metal(Field& f, std::uint64_t seed) {
  const Field streaks = NoiseField(f.n, Fbm(Stream(seed, 0), 1, 16, 3, 0.6, f.n));
  const Field sheen = NoiseField(f.n, Fbm(Stream(seed, 1), 2, 2, 2, 0.5, f.n));
  for (std::size_t i = 0; i < f.v.size(); ++i) f.v[i] = 0.5 * streaks.v[i] + sheen.v[i];
  SetMeanStd(f, 150.0, 1.5);
}

// Floor tiles 0.5 m square (2 × 2 per 1 m tile) with grout lines only a few grey levels
// darker than the tiles, so the grid barely registers as corners.
void HardFloor(Field& f, std::uint64_t seed) {
  const int n = f.n;
  const Field noise = NoiseField(n, Fbm(Stream(seed, 0), 4, 4, 3, 0.5, n));
  constexpr int kTiles = 2;
  double tone[kTiles * kTiles];
  for (int k = 0; k < kTiles * kTiles; ++k) tone[k] = GaussFromBits(HashPoint(seed, k, 0));
  const double pitch = 1.0 / kTiles;
  const double grout_half_px = 0.004 * n;  // 8 mm grout on a 1 m tile
  ForEachTexel(f, [&](int x, int y, double u, double v, double& value) {
    const int tile = static_cast<int>(v * kTiles) * kTiles + static_cast<int>(u * kTiles);
    const double d_px = std::min(DistanceToGrid(u, pitch), DistanceToGrid(v, pitch)) * n;
    value = 178.0 + 1.0 * tone[tile] + 0.9 * noise.at(x, y) - 5.0 * Coverage(d_px - grout_half_px);
  });
}

// Adds a filled rectangle [u0, u1] × [v0, v1] (tile units) of grey `tone`, antialiased.
void PaintRect(Field& f, double u0, double v0, double u1, double v1, double tone,
               double opacity = 1.0) {
  const int n = f.n;
  const double cx = 0.5 * (u0 + u1) * n;
  const double cy = 0.5 * (v0 + v1) * n;
  const double hx = 0.5 * (u1 - u0) * n;
  const double hy = 0.5 * (v1 - v0) * n;
  ForEachNear(
      f, cx, cy, std::max(hx, hy) + 1.0, [&](double& value, double dx, double dy, int, int) {
        const double c = Coverage(std::abs(dx) - hx) * Coverage(std::abs(dy) - hy) * opacity;
        value += c * (tone - value);
      });
}

// A wooden door leaf (1 m wide, two leaves side by side on a 2 m tile): a mid-grey
// panel, a slightly darker frame of stiles and rails, recessed panels whose bevels are
// a little darker on the shaded side and lighter on the lit side, and a handle plate.
void Door(Field& f, std::uint64_t seed) {
  const int n = f.n;
  const Field grain = NoiseField(n, Fbm(Stream(seed, 0), 24, 2, 3, 0.5, n));
  constexpr double kLeaf = 0.5;    // leaf width [tile] (1 m)
  constexpr double kStile = 0.03;  // half the width of the stile band at a leaf edge [tile]
  constexpr double kRail = 0.035;  // half the height of the top/bottom rail band [tile]
  constexpr double kLock0 = 0.52;  // lock rail between the upper and lower panel [tile]
  constexpr double kLock1 = 0.58;
  constexpr double kBevel = 0.012;  // bevel width [tile]
  ForEachTexel(f, [&](int x, int y, double u, double v, double& value) {
    const double ul = u - kLeaf * std::floor(u / kLeaf);  // position within the leaf
    value = 138.0 + 1.5 * grain.at(x, y);
    const bool frame = ul < kStile || ul > kLeaf - kStile || v < kRail || v > 1.0 - kRail ||
                       (v > kLock0 && v < kLock1);
    if (frame) {
      value -= 6.0;
      return;
    }
    // Inside a panel: distance to each of its four edges.
    const double top = v < kLock0 ? v - kRail : v - kLock1;
    const double bottom = v < kLock0 ? kLock0 - v : 1.0 - kRail - v;
    const double left = ul - kStile;
    const double right = kLeaf - kStile - ul;
    const double nearest = std::min(std::min(top, bottom), std::min(left, right));
    if (nearest < kBevel) {
      const bool shaded = nearest == top || nearest == left;  // faces away from the light
      value += shaded ? -9.0 : 5.0;
    }
  });
  for (int leaf = 0; leaf < 2; ++leaf) {
    const double u = leaf * kLeaf + kLeaf - kStile - 0.03;
    PaintRect(f, u - 0.007, 0.47, u + 0.007, 0.53, 110.0);
  }
}

// A poster: paper with a dark title bar carrying light lettering, a band of picture
// blocks in different grey levels, and rows of dark "words" below; the one indoor
// surface with corners. A paper margin all round keeps the tile seamless.
void Poster(Field& f, std::uint64_t seed) {
  const int n = f.n;
  Rng rng(Stream(seed, 0));
  f = NoiseField(n, Fbm(Stream(seed, 1), 3, 3, 2, 0.5, n));
  SetMeanStd(f, 232.0, 1.0);
  constexpr double kMargin = 0.1;
  const double title_tone = rng.Uniform(40.0, 90.0);
  PaintRect(f, kMargin, 0.1, 1.0 - kMargin, 0.21, title_tone);
  // Words: dashes of random length along a row, ragged at the right.
  auto words = [&](double v0, double height, double u_end, double tone) {
    double u = kMargin + 0.02;
    while (true) {
      const double len = rng.Uniform(0.02, 0.08);
      if (u + len > u_end) break;
      PaintRect(f, u, v0, u + len, v0 + height, tone);
      u += len + rng.Uniform(0.012, 0.02);
    }
  };
  words(0.14, 0.035, 1.0 - kMargin - 0.15, 225.0);
  // Picture blocks: 2–3 side by side, one with an inset.
  const int blocks = 2 + static_cast<int>(rng.Uniform() * 2.0);
  double u = kMargin;
  const double width_total = 1.0 - 2.0 * kMargin - 0.02 * (blocks - 1);
  for (int b = 0; b < blocks; ++b) {
    const double w = width_total / blocks;
    const double tone = rng.Uniform(70.0, 200.0);
    PaintRect(f, u, 0.25, u + w, 0.56, tone);
    if (b == 0) {
      const double inset = rng.Uniform(40.0, 230.0);
      PaintRect(f, u + 0.2 * w, 0.3, u + 0.7 * w, 0.45, inset);
    }
    u += w + 0.02;
  }
  for (double v = 0.61; v < 0.88; v += 0.034) {
    const double u_end = 1.0 - kMargin - rng.Uniform(0.0, 0.2);
    words(v, 0.013, u_end, 60.0);
  }
}

// ---------------------------------------------------------------------------
// Outdoor appearances: high-contrast detail at 3–30 texels (many trackable corners).

// Grass seen from above: thousands of tapered blades in all directions, lighter at the
// tips, over dark ground with lawn-scale patches.
void Grass(Field& f, std::uint64_t seed) {
  const int n = f.n;
  f = NoiseField(n, Fbm(Stream(seed, 0), 4, 4, 5, 0.55, n));
  SetMeanStd(f, 45.0, 10.0);
  const Fbm patches(Stream(seed, 1), 3, 3, 2, 0.5, n);
  Rng rng(Stream(seed, 2));
  constexpr int kBlades = 9000;
  for (int k = 0; k < kBlades; ++k) {
    const double ax = rng.Uniform() * n;
    const double ay = rng.Uniform() * n;
    const Eigen::Vector2d dir = rng.Direction();
    const double len = rng.Uniform(0.025, 0.075) * n;
    const double half_width = rng.Uniform(0.0025, 0.0045) * n;
    const bool dark = rng.Chance(0.3);
    const double base_tone = dark ? rng.Uniform(20.0, 50.0) : rng.Uniform(80.0, 170.0);
    const double tone = base_tone + 25.0 * patches(ax / n, ay / n);
    const Eigen::Vector2d mid = Eigen::Vector2d(ax, ay) + 0.5 * len * dir;
    const Eigen::Vector2d box = EllipseExtent(0.5 * len + half_width, half_width, dir);
    ForEachInBox(f, mid.x(), mid.y(), box.x() + 1.0, box.y() + 1.0,
                 [&](double& value, double dx, double dy, int, int) {
                   // Most of the window is far from the thin blade: reject it cheaply.
                   const double perp = dx * dir.y() - dy * dir.x();
                   if (std::abs(perp) >= half_width + 0.5) return;
                   const double along = dx * dir.x() + dy * dir.y() + 0.5 * len;
                   const double t = Clamp01(along / len);
                   const double beyond = along - t * len;  // past an end, else 0
                   const double across = std::sqrt(perp * perp + beyond * beyond);
                   const double c = Coverage(across - half_width * (1.0 - 0.75 * t));
                   if (c > 0.0) value += c * (tone * (0.8 + 0.4 * t) - value);
                 });
  }
  SetMeanStd(f, 95.0, 42.0);
}

// Billowy noise: octaves of |gradient noise|, i.e. rounded lumps between creases.
Field Billows(int n, std::uint64_t seed, int period, int octaves) {
  std::vector<GradientNoise> layers;
  for (int k = 0; k < octaves && (period << k) <= n; ++k) {
    layers.emplace_back(Stream(seed, static_cast<std::uint64_t>(k)), period << k, period << k);
  }
  Field f(n);
  ForEachTexel(f, [&](int, int, double u, double v, double& value) {
    double amplitude = 1.0;
    for (const GradientNoise& layer : layers) {
      value += amplitude * std::abs(layer(u, v));
      amplitude *= 0.5;
    }
  });
  return f;
}

// Bare earth: a heap of clods (wobbly domes of random size, merged by height) on lumpy
// ground, lit from one side, with dark hollows where no clod lies, moist and dry
// patches and scattered light grains.
struct EarthLook {
  int clods = 900;                ///< Clods per tile.
  double clod_radius = 0.045;     ///< Largest clod radius [tile].
  double hollow_darkness = 35.0;  ///< Grey levels lost where no clod covers the ground.
  int grains = 400;               ///< Light grains (sand, small stones) per tile.
  double grain_radius = 0.006;    ///< Largest grain radius [tile].
  double mean = 110.0;            ///< Final mean grey level.
  double sd = 32.0;               ///< Final standard deviation [grey levels].
};

void Earth(Field& f, std::uint64_t seed, const EarthLook& look) {
  const int n = f.n;
  Field height = Billows(n, Stream(seed, 0), 6, 4);
  for (double& h : height.v) h *= 0.01;
  const Field wobble = NoiseField(n, Fbm(Stream(seed, 1), 24, 24, 2, 0.5, n));
  Field clod_height(n);
  Field tone(n);
  Rng rng(Stream(seed, 2));
  for (int k = 0; k < look.clods; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double radius = rng.Uniform(0.3, 1.0) * look.clod_radius * n;
    const double flatness = rng.Uniform(0.4, 0.9);
    const double clod_tone = 12.0 * rng.Gauss();
    ForEachNear(clod_height, cx, cy, 1.25 * radius + 1.0,
                [&](double& h, double dx, double dy, int x, int y) {
                  // Wobble within ±20 % keeps the clod inside its window.
                  const double w = 1.0 + 0.2 * std::min(1.2, std::max(-1.2, wobble.at(x, y)));
                  const double r = std::sqrt(dx * dx + dy * dy) / (radius * w);
                  if (r >= 1.0) return;
                  const double dome = flatness * radius / n * std::sqrt(1.0 - r * r);
                  if (dome > h) {
                    h = dome;
                    tone.at(x, y) = clod_tone;
                  }
                });
  }
  for (std::size_t i = 0; i < f.v.size(); ++i) height.v[i] += clod_height.v[i];
  Field relief = Relief(height, kLightX, kLightY, kLightZ);
  SetMeanStd(relief, 0.0, 1.0);
  const Field patches = NoiseField(n, Fbm(Stream(seed, 3), 3, 3, 4, 0.55, n));
  const double px = 1.0 / n;  // one texel [tile]
  for (std::size_t i = 0; i < f.v.size(); ++i) {
    const double hollow = 1.0 - SmoothStep(0.0, px, clod_height.v[i]);
    f.v[i] = 110.0 + 28.0 * relief.v[i] + tone.v[i] + 12.0 * patches.v[i] -
             look.hollow_darkness * hollow;
  }
  for (int k = 0; k < look.grains; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double radius = rng.Uniform(0.3, 1.0) * look.grain_radius * n;
    const double g = rng.Uniform(150.0, 210.0);
    ForEachNear(f, cx, cy, radius + 1.0, [&](double& value, double dx, double dy, int, int) {
      const double r = std::sqrt(dx * dx + dy * dy);
      const double lit = Clamp01(0.7 - 0.5 * (dx * kLightX + dy * kLightY) / (radius + 0.5));
      value += Coverage(r - radius) * (g * (0.6 + 0.5 * lit) - value);
    });
  }
  SetMeanStd(f, look.mean, look.sd);
}

void Soil(Field& f, std::uint64_t seed) { Earth(f, seed, EarthLook{}); }

void SandyLoam(Field& f, std::uint64_t seed) {
  EarthLook look;
  look.clods = 2000;
  look.clod_radius = 0.028;
  look.hollow_darkness = 25.0;
  look.grains = 2500;
  look.grain_radius = 0.004;
  look.mean = 92.0;
  look.sd = 30.0;
  Earth(f, seed, look);
}

// Sand: a height field of wind ripples (asymmetric, meandering) or footprints, plus
// fine grain, shaded by the light, with scattered dark and light grains.
struct SandLook {
  double ripple_height = 1.0;  ///< Ripple amplitude (relative).
  int footprints = 0;          ///< Footprints per tile.
  double mean = 185.0;         ///< Final mean grey level.
  double sd = 26.0;            ///< Final standard deviation [grey levels].
};

// An asymmetric ripple profile of period 1: a long gentle stoss slope, a short steep lee.
double Ripple(double t) {
  const double f = t - std::floor(t);
  constexpr double kCrest = 0.75;
  return f < kCrest ? SmoothStep(0.0, kCrest, f) : 1.0 - SmoothStep(kCrest, 1.0, f);
}

void Sand(Field& f, std::uint64_t seed, const SandLook& look) {
  const int n = f.n;
  Rng rng(Stream(seed, 0));
  // Integer wave numbers keep the ripples periodic over the tile.
  const int kx = static_cast<int>(rng.Uniform(-3.0, 4.0));
  const int ky = 9 + static_cast<int>(rng.Uniform(0.0, 5.0));
  const double wavelength = 1.0 / std::sqrt(static_cast<double>(kx * kx + ky * ky));
  const Fbm meander(Stream(seed, 1), 2, 2, 3, 0.5, n);
  const Fbm lumps(Stream(seed, 2), 6, 6, 4, 0.5, n);
  const Fbm grain(Stream(seed, 3), std::min(n / 2, 64), std::min(n / 2, 64), 2, 0.5, n);
  Field height(n);
  ForEachTexel(height, [&](int, int, double u, double v, double& h) {
    const double phase = kx * u + ky * v + 1.2 * meander(u, v);
    h = look.ripple_height * 0.25 * wavelength * Ripple(phase) + 0.004 * lumps(u, v) +
        0.0009 * grain(u, v);
  });
  // Footprints: pairs of steps 0.6 m apart, left and right, each a
  // shoe-shaped depression (waisted between heel and ball) with a tread of cross ribs
  // and a rim of displaced sand.
  constexpr int kStepsPerTrail = 2;
  for (int trail = 0; kStepsPerTrail * trail < look.footprints; ++trail) {
    const double sx = rng.Uniform();
    const double sy = rng.Uniform();
    const Eigen::Vector2d dir = rng.Direction();
    const Eigen::Vector2d side(-dir.y(), dir.x());
    const int steps = std::min(kStepsPerTrail, look.footprints - kStepsPerTrail * trail);
    for (int step = 0; step < steps; ++step) {
      const double sgn = step % 2 == 0 ? 1.0 : -1.0;
      const Eigen::Vector2d c =
          (Eigen::Vector2d(sx, sy) + 0.6 * step * dir + 0.07 * sgn * side) * n;
      const double a = 0.14 * n;   // half length
      const double b = 0.048 * n;  // half width
      ForEachNear(height, c.x(), c.y(), a * 1.4, [&](double& h, double dx, double dy, int, int) {
        const double s = (dx * dir.x() + dy * dir.y()) / a;
        const double waist = 1.0 - 0.3 * (1.0 - SmoothStep(0.0, 0.35, std::abs(s + 0.25)));
        const double t = (-dx * dir.y() + dy * dir.x()) / (b * waist);
        const double r2 = s * s + t * t;
        if (r2 < 1.0) {
          const double floor_depth = (1.0 - r2) * (1.0 - r2);
          h -= 0.012 * floor_depth - 0.002 * SmoothStep(0.0, 0.3, floor_depth) * Wave(4.0 * s);
        }
        if (r2 > 0.64 && r2 < 1.96) {
          const double q = (r2 - 1.3) / 0.66;
          h += 0.004 * (1.0 - q * q);
        }
      });
    }
  }
  Field relief = Relief(height, kLightX, kLightY, kLightZ);
  SetMeanStd(relief, 0.0, 1.0);
  const Field albedo = NoiseField(n, Fbm(Stream(seed, 4), 4, 4, 3, 0.5, n));
  for (std::size_t i = 0; i < f.v.size(); ++i) f.v[i] = 30.0 * relief.v[i] + 6.0 * albedo.v[i];
  constexpr int kGrains = 3000;
  for (int k = 0; k < kGrains; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double radius = rng.Uniform(0.0012, 0.004) * n;
    const double delta = rng.Chance(0.6) ? rng.Uniform(-70.0, -30.0) : rng.Uniform(30.0, 60.0);
    ForEachNear(f, cx, cy, radius + 1.0, [&](double& value, double dx, double dy, int, int) {
      value += Coverage(std::sqrt(dx * dx + dy * dy) - radius) * delta;
    });
  }
  SetMeanStd(f, look.mean, look.sd);
}

void DrySand(Field& f, std::uint64_t seed) { Sand(f, seed, SandLook{}); }

void LeteSand(Field& f, std::uint64_t seed) {
  SandLook look;
  look.ripple_height = 0.2;
  look.footprints = 6;  // three pairs of steps
  look.mean = 170.0;
  look.sd = 26.0;
  Sand(f, seed, look);
}

// Dry clay: plates separated by a meandering polygonal crack network (Voronoi borders,
// domain-warped), a finer partial network inside the plates, curled lighter plate edges.
void Clay(Field& f, std::uint64_t seed) {
  const int n = f.n;
  const Fbm warp_u(Stream(seed, 0), 4, 4, 2, 0.5, n);
  const Fbm warp_v(Stream(seed, 1), 4, 4, 2, 0.5, n);
  constexpr int kPlates = 7;
  constexpr int kFine = 18;
  const Cells plates(Stream(seed, 2), kPlates, kPlates, 0.85);
  const Cells fine(Stream(seed, 3), kFine, kFine, 0.9);
  const GradientNoise width(Stream(seed, 4), 5, 5);
  const GradientNoise fine_mask(Stream(seed, 5), 3, 3);
  const Field mottle = NoiseField(n, Fbm(Stream(seed, 6), 6, 6, 3, 0.6, n));
  const GradientNoise grain(Stream(seed, 7), std::min(n / 2, 128), std::min(n / 2, 128));
  Field height(n);
  ForEachTexel(f, [&](int x, int y, double u, double v, double& value) {
    const double wu = u + 0.03 * warp_u(u, v);
    const double wv = v + 0.03 * warp_v(u, v);
    const Cells::Sample big = plates(wu, wv, std::max(0.04, 0.008 + 1.0 / n));
    const double edge_px = big.edge * n;
    // The crack and the fine network only where they can show (saves most of the work);
    // Cells report borders up to the distance where the antialiased line fades out.
    double crack = 0.0;
    if (edge_px < 0.008 * n + 0.5) crack = Coverage(edge_px - (0.0045 + 0.004 * width(u, v)) * n);
    double fine_crack = SmoothStep(-0.05, 0.15, fine_mask(u, v));
    if (fine_crack > 0.0) {
      fine_crack *= Coverage(fine(wu, wv, 0.0016 + 1.0 / n).edge * n - 0.0016 * n);
    }
    const double plate = 88.0 + 10.0 * GaussFromBits(HashPoint(seed, big.id, 0)) +
                         8.0 * mottle.at(x, y) + 6.0 * grain(u, v) +
                         16.0 * (1.0 - SmoothStep(0.0, 0.03 * n, edge_px));
    value = Lerp(plate, 22.0, crack) * (1.0 - 0.55 * fine_crack);
    height.at(x, y) = 0.01 * SmoothStep(0.0, 0.025 * n, edge_px);
  });
  const Field relief = Relief(height, kLightX, kLightY, kLightZ);
  for (std::size_t i = 0; i < f.v.size(); ++i) f.v[i] += 25.0 * relief.v[i];
  SetMeanStd(f, 80.0, 30.0);
}

// Gravel: many overlapping stones (wobbly ellipses, domed and lit, with dark rims and
// a drop shadow) over dark gaps.
void Gravel(Field& f, std::uint64_t seed) {
  const int n = f.n;
  f = NoiseField(n, Fbm(Stream(seed, 0), 16, 16, 3, 0.5, n));
  SetMeanStd(f, 35.0, 8.0);
  const Field wobble = NoiseField(n, Fbm(Stream(seed, 1), 24, 24, 2, 0.5, n));
  Rng rng(Stream(seed, 2));
  constexpr int kStones = 1100;
  for (int k = 0; k < kStones; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double a = rng.Uniform(0.014, 0.04) * n;
    const double b = a * rng.Uniform(0.55, 0.95);
    const Eigen::Vector2d d = rng.Direction();
    const double tone = rng.Uniform(90.0, 215.0);
    const std::uint64_t speck = rng.Next();
    // The stone's shape test: (s, t) in its own frame, normalised by the semi-axes.
    auto local = [&](double dx, double dy, int x, int y) {
      const double s = (dx * d.x() + dy * d.y()) / a;
      const double t = (-dx * d.y() + dy * d.x()) / b;
      const double w = 1.0 + 0.06 * std::min(3.0, std::max(-3.0, wobble.at(x, y)));
      return Eigen::Vector3d(s, t, std::sqrt(s * s + t * t) / w);
    };
    const double shadow = 0.35 * b;
    const Eigen::Vector2d box = 1.2 * EllipseExtent(a, b, d) + Eigen::Vector2d(1.0, 1.0);
    ForEachInBox(f, cx - shadow * kLightX, cy - shadow * kLightY, box.x(), box.y(),
                 [&](double& value, double dx, double dy, int x, int y) {
                   const double r = local(dx, dy, x, y).z();
                   value *= 1.0 - 0.5 * Coverage((r - 1.0) * b);
                 });
    ForEachInBox(
        f, cx, cy, box.x(), box.y(), [&](double& value, double dx, double dy, int x, int y) {
          const Eigen::Vector3d q = local(dx, dy, x, y);
          const double c = Coverage((q.z() - 1.0) * b);
          if (c <= 0.0) return;
          const double rr = std::min(q.z(), 1.0);
          const double lambert =
              std::max(0.0, Lambert(q.x() * d.x() - q.y() * d.y(), q.x() * d.y() + q.y() * d.x(),
                                    1.2 * std::sqrt(1.0 - rr * rr), kLightX, kLightY, kLightZ));
          const double rim = SmoothStep(0.75, 1.0, rr);
          const double grain = 12.0 * (UnitFromBits(HashPoint(speck, x, y)) - 0.5);
          const double stone = tone * (0.3 + 0.8 * lambert) * (1.0 - 0.45 * rim) + grain;
          value += c * (stone - value);
        });
  }
  SetMeanStd(f, 115.0, 42.0);
}

// Concrete paving slabs 0.4 m square, 4 × 4 on a 1.6 m tile: dark joints, dirt along
// the joints, per-slab tone, stains, and aggregate speckle.
void Paving(Field& f, std::uint64_t seed) {
  const int n = f.n;
  constexpr int kSlabs = 4;
  const double pitch = 1.0 / kSlabs;
  const double joint_half_px = 0.005 / 1.6 * n;  // 10 mm joints
  const Field stains = NoiseField(n, Fbm(Stream(seed, 0), 3, 3, 4, 0.55, n));
  const Fbm fine(Stream(seed, 1), std::min(n / 4, 64), std::min(n / 4, 64), 2, 0.5, n);
  ForEachTexel(f, [&](int x, int y, double u, double v, double& value) {
    const int slab = static_cast<int>(v * kSlabs) * kSlabs + static_cast<int>(u * kSlabs);
    const double d_px = std::min(DistanceToGrid(u, pitch), DistanceToGrid(v, pitch)) * n;
    const double dirt = 1.0 - SmoothStep(0.0, 0.012 * n, d_px - joint_half_px);
    const double slab_tone = 150.0 + 10.0 * GaussFromBits(HashPoint(seed, slab, 0));
    const double surface = slab_tone + 9.0 * stains.at(x, y) + 10.0 * fine(u, v) - 14.0 * dirt;
    value = Lerp(surface, 55.0, Coverage(d_px - joint_half_px));
  });
  Rng rng(Stream(seed, 2));
  constexpr int kSpecks = 9000;
  for (int k = 0; k < kSpecks; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double radius = rng.Uniform(0.0015, 0.005) * n;
    const double delta = rng.Chance(0.5) ? rng.Uniform(-55.0, -25.0) : rng.Uniform(20.0, 45.0);
    ForEachNear(f, cx, cy, radius + 1.0, [&](double& value, double dx, double dy, int, int) {
      value += Coverage(std::sqrt(dx * dx + dy * dy) - radius) * delta;
    });
  }
  SetMeanStd(f, 135.0, 28.0);
}

// Brickwork in running bond: 215 × 65 mm bricks, 10 mm mortar, so a 225 × 75 mm module.
// 4 modules across and 12 courses down make a 0.9 m square tile (12 is even, as the bond
// repeats every two courses). Per-brick tone, speckle, ragged edges, shadowed bed joints.
constexpr double kBrickTileM = 0.9;

void Brick(Field& f, std::uint64_t seed) {
  const int n = f.n;
  constexpr int kAcross = 4;
  constexpr int kCourses = 12;
  const double mortar_half_px = 0.005 / kBrickTileM * n;
  const Fbm ragged(Stream(seed, 0), 32, 32, 2, 0.5, n);
  const Field blotch = NoiseField(n, Fbm(Stream(seed, 1), 16, 16, 3, 0.5, n));
  const GradientNoise speckle(Stream(seed, 2), std::min(n / 2, 128), std::min(n / 2, 128));
  ForEachTexel(f, [&](int x, int y, double u, double v, double& value) {
    const int course = std::min(static_cast<int>(v * kCourses), kCourses - 1);
    const double shift = course % 2 == 0 ? 0.0 : 0.5 / kAcross;
    const double along = u - shift + 1.0;  // positive, so floor is a brick index
    const int column = static_cast<int>(along * kAcross) % kAcross;
    const int id = course * kAcross + column;
    const double du_px = DistanceToGrid(along, 1.0 / kAcross) * n;
    const double bed = v * kCourses - std::floor(v * kCourses + 0.5);  // signed, in courses
    const double dv_px = std::abs(bed) / kCourses * n;
    const double d_px = std::min(du_px, dv_px) + 0.7 * ragged(u, v);
    const double brick = 118.0 + 20.0 * GaussFromBits(HashPoint(seed, id, 0)) +
                         7.0 * blotch.at(x, y) + 14.0 * speckle(u, v);
    // The bed joint's upper half lies in the shadow of the brick above it.
    const double mortar = 185.0 + 8.0 * speckle(v, u) - (bed < 0.0 && dv_px <= du_px ? 45.0 : 0.0);
    value = Lerp(brick, mortar, Coverage(d_px - mortar_half_px));
  });
  Rng rng(Stream(seed, 3));
  constexpr int kSpecks = 700;
  for (int k = 0; k < kSpecks; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double radius = rng.Uniform(0.002, 0.005) * n;
    ForEachNear(f, cx, cy, radius + 1.0, [&](double& value, double dx, double dy, int, int) {
      value -= 35.0 * Coverage(std::sqrt(dx * dx + dy * dy) - radius);
    });
  }
}

// Tree bark (0.5 m tile): long interlaced ridges between deep dark furrows, as the
// borders of Voronoi cells on a lattice 12 across by 2 along the trunk, warped so the
// furrows meander; furrows vary in width, ridges carry fibrous vertical striations and
// per-plate tone, lit from the side, with short dark lenticels.
void Bark(Field& f, std::uint64_t seed) {
  const int n = f.n;
  const Fbm meander_u(Stream(seed, 0), 2, 6, 2, 0.5, n);
  const Fbm meander_v(Stream(seed, 1), 4, 4, 2, 0.5, n);
  const Cells plates(Stream(seed, 2), 12, 2, 1.0);
  const GradientNoise width(Stream(seed, 3), 6, 3);
  const Fbm fibres(Stream(seed, 4), std::min(n / 4, 64), 4, 2, 0.6, n);
  const Field tone = NoiseField(n, Fbm(Stream(seed, 5), 4, 4, 3, 0.5, n));
  Field height(n);
  Field fissure(n);
  Field plate_tone(n);
  ForEachTexel(height, [&](int x, int y, double u, double v, double& h) {
    const double wu = u + 0.03 * meander_u(u, v);
    const double wv = v + 0.05 * meander_v(u, v);
    const Cells::Sample s = plates(wu, wv, 0.03 + 1.0 / n);
    const double edge_px = s.edge * n;
    const double half_width_px = (0.011 + 0.007 * width(u, v)) * n;
    fissure.at(x, y) = 1.0 - SmoothStep(0.3 * half_width_px, half_width_px + 0.5, edge_px);
    const double size = 0.7 + 0.3 * UnitFromBits(HashPoint(seed, s.id, 0));
    h = 0.012 * size * SmoothStep(0.0, 0.03, s.edge) + 0.0012 * fibres(wu, v);
    plate_tone.at(x, y) = 12.0 * GaussFromBits(HashPoint(seed, s.id, 1));
  });
  Field relief = Relief(height, kLightX, 0.3 * kLightY, kLightZ);
  SetMeanStd(relief, 0.0, 1.0);
  for (std::size_t i = 0; i < f.v.size(); ++i) {
    f.v[i] = 120.0 + plate_tone.v[i] + 8.0 * tone.v[i] + 25.0 * relief.v[i] - 85.0 * fissure.v[i];
  }
  // Lenticels: short dark horizontal dashes across the ridges.
  Rng rng(Stream(seed, 6));
  constexpr int kLenticels = 80;
  for (int k = 0; k < kLenticels; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double half_len = rng.Uniform(0.005, 0.015) * n;
    const double half_thick = std::max(0.5, 0.002 * n);
    ForEachInBox(f, cx, cy, half_len + 1.0, half_thick + 1.0,
                 [&](double& value, double dx, double dy, int, int) {
                   const double c =
                       Coverage(std::abs(dx) - half_len) * Coverage(std::abs(dy) - half_thick);
                   value += c * (30.0 - value) * 0.8;
                 });
  }
  SetMeanStd(f, 95.0, 40.0);
}

// Bench slats: eight 125 mm planks along u with dark gaps, growth-ring grain lines
// that meander, fibres, weathering, a butt joint per plank, screws, knots and checks.
void Wood(Field& f, std::uint64_t seed) {
  const int n = f.n;
  constexpr int kSlats = 8;
  const Fbm meander(Stream(seed, 0), 2, 8, 3, 0.5, n);
  const Fbm fibres(Stream(seed, 1), 4, std::min(n / 2, 96), 2, 0.5, n);
  const Field weather = NoiseField(n, Fbm(Stream(seed, 2), 3, 3, 3, 0.5, n));
  const double gap_half_px = 0.004 * n;
  Rng rng(Stream(seed, 3));
  double slat_tone[kSlats];
  double rings[kSlats];
  double joint[kSlats];
  for (int k = 0; k < kSlats; ++k) {
    slat_tone[k] = 140.0 + 14.0 * rng.Gauss();
    rings[k] = rng.Uniform(5.0, 9.0);
    joint[k] = rng.Uniform();
  }
  ForEachTexel(f, [&](int x, int y, double u, double v, double& value) {
    const int k = std::min(static_cast<int>(v * kSlats), kSlats - 1);
    const double across = v * kSlats - k;  // 0…1 across the plank
    const double phase = rings[k] * (across + 0.25 * meander(u, v)) + 0.37 * k;
    const double w = 0.5 + 0.5 * Wave(phase);
    const double late = w * w * w * w;  // thin dark latewood lines
    double value_here = slat_tone[k] + 8.0 * Wave(phase) - 45.0 * late + 7.0 * fibres(u, v) +
                        8.0 * weather.at(x, y);
    const double gap_px = DistanceToGrid(v, 1.0 / kSlats) * n;
    const double joint_px = DistanceToGrid(u - joint[k], 1.0) * n;
    value_here = Lerp(value_here, 30.0, Coverage(gap_px - gap_half_px));
    value = Lerp(value_here, 45.0, Coverage(joint_px - 0.5 * gap_half_px));
  });
  for (int k = 0; k < kSlats; ++k) {
    const double vc = (k + 0.5) / kSlats;
    for (const double us : {0.12, 0.62}) {
      for (const double side : {-0.25, 0.25}) {
        const double cx = us * n;
        const double cy = (vc + side / kSlats) * n;
        const double radius = 0.006 * n;
        ForEachNear(f, cx, cy, radius + 1.0, [&](double& value, double dx, double dy, int, int) {
          const double r = std::sqrt(dx * dx + dy * dy);
          value += Coverage(r - radius) * ((dx + dy < 0.0 ? 120.0 : 40.0) - value);
        });
      }
    }
    const int knots = static_cast<int>(rng.Uniform(0.0, 2.5));
    for (int j = 0; j < knots; ++j) {
      const double cx = rng.Uniform() * n;
      const double cy = (k + rng.Uniform(0.3, 0.7)) / kSlats * n;
      const double a = rng.Uniform(0.02, 0.04) * n;
      const double b = 0.45 * a;
      ForEachInBox(f, cx, cy, a + 1.0, b + 1.0, [&](double& value, double dx, double dy, int, int) {
        const double r = std::sqrt((dx / a) * (dx / a) + (dy / b) * (dy / b));
        const double ring = 0.5 + 0.5 * Wave(2.5 * r);
        value += Coverage((r - 1.0) * b) * ((70.0 + 40.0 * ring) - value);
      });
    }
    // Checks: short drying cracks along the grain.
    const int checks = 4 + static_cast<int>(rng.Uniform(0.0, 6.0));
    for (int j = 0; j < checks; ++j) {
      const double cx = rng.Uniform() * n;
      const double cy = (k + rng.Uniform(0.15, 0.85)) / kSlats * n;
      const double half_len = rng.Uniform(0.01, 0.035) * n;
      const double half_thick = std::max(0.45, 0.0015 * n);
      ForEachInBox(f, cx, cy, half_len + 1.0, half_thick + 1.0,
                   [&](double& value, double dx, double dy, int, int) {
                     const double taper = 1.0 - std::abs(dx) / (half_len + 1.0);
                     const double c =
                         Coverage(std::abs(dx) - half_len) * Coverage(std::abs(dy) - half_thick);
                     value += 0.85 * c * taper * (35.0 - value);
                   });
    }
  }
  SetMeanStd(f, 125.0, 32.0);
}

// Foliage: overlapping lens-shaped leaves with a midrib and a folded, unevenly lit
// blade, each casting a shadow, over deep shadow; upper layers are brighter.
void Leaves(Field& f, std::uint64_t seed) {
  const int n = f.n;
  f = NoiseField(n, Fbm(Stream(seed, 0), 8, 8, 3, 0.5, n));
  SetMeanStd(f, 25.0, 8.0);
  Rng rng(Stream(seed, 1));
  constexpr int kLeaves = 2600;
  for (int k = 0; k < kLeaves; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const Eigen::Vector2d d = rng.Direction();
    const double half_len = rng.Uniform(0.013, 0.03) * n;
    const double half_width = half_len * rng.Uniform(0.35, 0.5);
    const double depth = 0.65 + 0.35 * k / kLeaves;
    const double tone = rng.Uniform(70.0, 200.0) * depth;
    // Signed distance-like value of the lens |t| < w (1 − s²), in px.
    auto outside = [&](double dx, double dy, double* across) {
      const double s = (dx * d.x() + dy * d.y()) / half_len;
      const double t = -dx * d.y() + dy * d.x();
      *across = t;
      const double w = half_width * std::max(0.0, 1.0 - s * s);
      return std::max(std::abs(t) - w, (std::abs(s) - 1.0) * half_len);
    };
    const double shadow = 0.3 * half_width;
    const Eigen::Vector2d box = EllipseExtent(half_len, half_width, d) + Eigen::Vector2d(1.0, 1.0);
    ForEachInBox(f, cx - shadow * kLightX, cy - shadow * kLightY, box.x(), box.y(),
                 [&](double& value, double dx, double dy, int, int) {
                   double across = 0.0;
                   value *= 1.0 - 0.55 * Coverage(outside(dx, dy, &across));
                 });
    ForEachInBox(f, cx, cy, box.x(), box.y(), [&](double& value, double dx, double dy, int, int) {
      double across = 0.0;
      const double c = Coverage(outside(dx, dy, &across));
      if (c <= 0.0) return;
      const double fold = across > 0.0 ? 1.0 : 0.8;
      const double rib = 1.0 - 0.3 * Coverage(std::abs(across) - 0.4);
      value += c * (tone * fold * rib - value);
    });
  }
  SetMeanStd(f, 95.0, 45.0);
}

// A pedestrian's jacket: quilted baffles with stitched seams, a reflective stripe and a
// contrast stripe, two pockets with stitched flaps, a zip with teeth, a logo patch and a twill
// weave with heathered yarn.
void Person(Field& f, std::uint64_t seed) {
  const int n = f.n;
  Rng rng(Stream(seed, 0));
  const double base = rng.Uniform(55.0, 95.0);
  const GradientNoise heather(Stream(seed, 1), std::min(n / 2, 128), std::min(n / 2, 128));
  constexpr int kBaffles = 10;
  ForEachTexel(f, [&](int, int, double u, double v, double& value) {
    const double along = v * kBaffles - std::floor(v * kBaffles);
    const double puff = 1.0 - (2.0 * along - 1.0) * (2.0 * along - 1.0);
    const double seam_px = DistanceToGrid(v, 1.0 / kBaffles) * n;
    const double twill = Wave(64.0 * (u + v));
    value = base - 10.0 + 20.0 * puff + 4.0 * twill + 8.0 * heather(u, v);
    value = Lerp(value, base - 35.0, Coverage(seam_px - 0.6));
    // Stitching 2.5 mm either side of the seam: light dashes, 80 per tile.
    const double stitch_px = std::abs(seam_px - 0.0025 * n);
    const double dash = SmoothStep(0.0, 0.3, Wave(80.0 * u));
    value = Lerp(value, base + 45.0, Coverage(stitch_px - 0.5) * dash);
  });
  const double stripe_tone = rng.Uniform(140.0, 170.0);
  PaintRect(f, -0.01, 0.30, 1.01, 0.345, 210.0);
  PaintRect(f, -0.01, 0.70, 1.01, 0.73, stripe_tone);
  // Pockets with a flap and a dashed light stitch line.
  for (const double u0 : {0.12, 0.68}) {
    PaintRect(f, u0, 0.46, u0 + 0.2, 0.62, base + 12.0);
    PaintRect(f, u0, 0.46, u0 + 0.2, 0.505, base - 15.0);
    for (double u = u0 + 0.01; u + 0.008 < u0 + 0.19; u += 0.016) {
      PaintRect(f, u, 0.513, u + 0.008, 0.517, base + 60.0);
    }
  }
  // The zip: a dark tape down the middle with light teeth (an integer count per tile).
  PaintRect(f, 0.494, -0.01, 0.506, 1.01, 30.0);
  constexpr int kTeeth = 48;
  for (int t = 0; t < kTeeth; ++t) {
    const double v = (t + 0.25) / kTeeth;
    const double u = t % 2 == 0 ? 0.492 : 0.5;
    PaintRect(f, u, v, u + 0.008, v + 0.5 / kTeeth, 150.0);
  }
  // Logo patch with three dark marks.
  PaintRect(f, 0.62, 0.14, 0.74, 0.2, 200.0);
  for (int m = 0; m < 3; ++m) {
    const double u = 0.63 + 0.038 * m;
    PaintRect(f, u, 0.15, u + 0.025, 0.19, 40.0);
  }
}

// ---------------------------------------------------------------------------
// The registry.

struct Recipe {
  const char* name;
  double meters_per_repeat;  ///< [m]
  void (*make)(Field&, std::uint64_t);
  /// How a ground's tiles vary under stochastic tiling (procedural_texture.h).
  TileVariation tiling = {};
  /// Adds variant k's own features to `make`'s surface; null: one variant.
  void (*features)(Field&, std::uint64_t, int) = nullptr;
};

// Free turns, mirrors and shifts for textures without a direction or a grid; a grid's
// (paving's slabs, the floor's tiles) shifts by whole cells; wind ripples keep their
// direction and their lee side.
constexpr TileVariation kAnyWay{4, true, 0, 1};
constexpr TileVariation kRipples{1, false, 0, 1};

// Sorted by name.
constexpr Recipe kRecipes[] = {
    {"asphalt", 1.0, AsphaltSurface, {4, true, 2, kAsphaltVariants}, AsphaltFeatures},
    {"bark", 0.5, Bark},
    {"brick", kBrickTileM, Brick},
    {"ceiling", 1.0, Ceiling},
    {"clay", 1.0, Clay, kAnyWay},
    {"door", 2.0, Door},
    {"door_frame", kFittingTileM, DoorFrame},
    {"dry_sand", 1.0, DrySand, kRipples},
    {"extinguisher", kFittingTileM, Extinguisher},
    {"facade", kFacadeTileM, Facade},
    {"grass", 1.0, Grass, kAnyWay},
    {"gravel", 1.0, Gravel, kAnyWay},
    {"hard_floor", 1.0, HardFloor, {4, true, 2, 1}},
    {"leaves", 1.0, Leaves},
    {"lete_sand", 1.0, LeteSand, kRipples},
    {"luminaire", kFittingTileM, Luminaire},
    {"metal", 1.0, Metal},
    {"notice_board", kBoardTileM, NoticeBoard},
    {"paving", 1.6, Paving, {4, true, 4, 1}},
    {"person", 1.0, Person},
    {"plain_paint", 1.0, PlainPaint},
    {"poster", 1.0, Poster},
    {"radiator", kFittingTileM, Radiator},
    {"sandy_loam", 1.0, SandyLoam, kAnyWay},
    {"skirting", kFittingTileM, Skirting},
    {"soil", 1.0, Soil, kAnyWay},
    {"switch_plate", kSwitchPlateTileM, SwitchPlate},
    {"wood", 1.0, Wood},
};

// The detailed look's own recipes of the robot's ground materials (docs/rendering.md,
// "Ground recipes"), each with variants: they replace the classic texture's variations
// under `ground_look: detailed`; MakeTexture keeps the classic one. Dry sand's variants
// agree at the tile's edges, but its tiles take any shift: without shifts the shared edges
// repeat at the tile's pitch (docs/rendering.md, "Ground recipes of the robot's materials").
constexpr Recipe kDetailedRecipes[] = {
    {"dry_sand", kSandTileM, SandSurface, {1, false, 0, kSandVariants}, SandFeatures},
    {"grass", kGrassTileM, GrassSurface, {4, true, 0, kGrassVariants}, GrassFeatures},
    {"sandy_loam", kSoilTileM, SoilSurface, {4, true, 0, kSoilVariants}, SoilFeatures},
};

const Recipe* FindRecipe(const std::string& name) {
  for (const Recipe& r : kRecipes) {
    if (name == r.name) return &r;
  }
  return nullptr;
}

// The recipe a ground of `name` is drawn with under the detailed look: its own detailed
// recipe if it has one, else `classic`.
const Recipe& GroundRecipe(const std::string& name, const Recipe& classic) {
  for (const Recipe& r : kDetailedRecipes) {
    if (name == r.name) return r;
  }
  return classic;
}

void CheckSize(const char* function, int size_px) {
  if (size_px < 16 || size_px > 2048 || (size_px & (size_px - 1)) != 0) {
    throw std::invalid_argument(std::string(function) +
                                ": size_px must be a power of two in [16, 2048], got " +
                                std::to_string(size_px));
  }
}

Texture Quantize(const Field& f, double meters_per_repeat) {
  Texture t;
  t.size_px = f.n;
  t.meters_per_repeat = meters_per_repeat;
  t.texels.resize(f.v.size());
  for (std::size_t i = 0; i < f.v.size(); ++i) {
    t.texels[i] =
        static_cast<std::uint8_t>(std::min(255.0, std::max(0.0, std::floor(f.v[i] + 0.5))));
  }
  return t;
}

}  // namespace

const std::vector<std::string>& TextureNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Recipe& r : kRecipes) out.emplace_back(r.name);
    return out;
  }();
  return names;
}

bool HasTexture(const std::string& appearance) { return FindRecipe(appearance) != nullptr; }

namespace {

const Recipe& KnownRecipe(const std::string& appearance) {
  const Recipe* recipe = FindRecipe(appearance);
  if (recipe == nullptr) {
    std::string known;
    for (const std::string& name : TextureNames()) known += (known.empty() ? "" : ", ") + name;
    throw std::invalid_argument("MakeTexture: unknown appearance '" + appearance +
                                "'; known: " + known);
  }
  return *recipe;
}

}  // namespace

Texture MakeTexture(const std::string& appearance, std::uint64_t seed, int size_px) {
  const Recipe& recipe = KnownRecipe(appearance);
  CheckSize("MakeTexture", size_px);
  Field f(size_px);
  const std::uint64_t s = Mix(seed ^ HashName(appearance));
  recipe.make(f, s);
  if (recipe.features != nullptr) recipe.features(f, s, 0);
  return Quantize(f, recipe.meters_per_repeat);
}

TileVariation GroundTileVariation(const std::string& appearance) {
  return GroundRecipe(appearance, KnownRecipe(appearance)).tiling;
}

std::vector<Texture> MakeTextureVariants(const std::string& appearance, std::uint64_t seed,
                                         int size_px) {
  const Recipe& recipe = GroundRecipe(appearance, KnownRecipe(appearance));
  if (recipe.features == nullptr) return {MakeTexture(appearance, seed, size_px)};
  CheckSize("MakeTextureVariants", size_px);
  Field surface(size_px);
  const std::uint64_t s = Mix(seed ^ HashName(appearance));
  recipe.make(surface, s);
  std::vector<Texture> out;
  for (int k = 0; k < recipe.tiling.variants; ++k) {
    Field f = surface;
    recipe.features(f, s, k);
    out.push_back(Quantize(f, recipe.meters_per_repeat));
  }
  return out;
}

Texture MakePlainTexture(double albedo, std::uint64_t seed, int size_px) {
  if (!(albedo >= 0.0 && albedo <= 1.0)) {
    throw std::invalid_argument("MakePlainTexture: albedo must be in [0, 1], got " +
                                std::to_string(albedo));
  }
  CheckSize("MakePlainTexture", size_px);
  Field f = NoiseField(size_px, Fbm(Stream(Mix(seed), 0), 2, 2, 2, 0.5, size_px));
  SetMeanStd(f, 255.0 * albedo, 0.8);
  return Quantize(f, 1.0);
}

}  // namespace trackbed::render
