// Bare sandy loam (see ground_soil.h). What it models and from where:
//
// - Aggregates: the size classes of granular soil structure (USDA Soil Survey Manual,
//   Agriculture Handbook 18, 2017: very fine under 1 mm, fine 1–2, medium 2–5, coarse
//   5–10, very coarse 10 mm and more); classes from 2 mm up are drawn (finer ones lie
//   below a 2 mm texel and make the fine earth's speckle), and clods of 20–50 mm left by
//   tillage. Counts per class are authored.
// - A surface crust where rain sealed the soil and it dried, broken by desiccation
//   cracks into polygons whose borders meet mostly at three-way junctions (crack networks
//   of cultivated soils lie between square and hexagonal ones: Velde 1999, Geoderma 93:
//   101). Polygons 5–8 cm across (authored: no spacing for a crusted sandy loam was
//   found); cracks 0.5–1.5 mm wide, so that they cover under the largest share measured
//   for a drying Vertisol, a crack intensity factor of 5.75 % (Lomeling et al. 2016,
//   Open J. Soil Sci. 6: 41) — a sandy loam shrinks less than a clay.
// - Sand grains: a sandy loam is over half sand (USDA texture triangle); its coarse sand
//   (0.5–2 mm) shows as light quartz specks. Bits of straw: a few per tile (authored).
// - Tones: grey = 255 × reflectance, the fine earth at `sandy_loam`'s albedo 0.40
//   (sim/terrain_material.cpp), the crust lighter by 10 % (a dry crust of fine
//   particles), cracks 0.05 (a shadowed gap), lit by the textures' light.
//
// Bit-exact as procedural_texture.cpp: no floating-point contraction, no libm.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "ground_soil.h"

#include <algorithm>
#include <cmath>

#include "texture_blocks.h"

namespace trackbed::render {

using namespace texture_blocks;  // NOLINT: the recipes are written in its terms

namespace {

constexpr double kEarthReflectance = 0.40;  // sandy_loam's albedo (sim/terrain_material.cpp)
constexpr double kSoilCrackReflectance = 0.05;
constexpr double kSoilGrey = 255.0;

std::uint64_t SoilStream(std::uint64_t seed, int variant) {
  return Stream(seed, 30 + static_cast<std::uint64_t>(variant));
}

// The crust's mask [0, 1] and its cracks' coverage [0, 1] per texel.
struct Crust {
  Field mask;
  Field crack;
  explicit Crust(int n) : mask(n), crack(n) {}
};

Crust MakeCrust(std::uint64_t seed, int variant, int n) {
  const std::uint64_t s = SoilStream(seed, variant);
  Rng rng(Stream(s, 0));
  const int cells = 6 + static_cast<int>(rng.Uniform() * 5.0);  // 6–10 per 0.5 m: 5–8 cm
  const Cells polygons(Stream(s, 1), cells, cells, 0.9);
  const Fbm warp_u(Stream(s, 2), 4, 4, 2, 0.5, n);
  const Fbm warp_v(Stream(s, 3), 4, 4, 2, 0.5, n);
  const GradientNoise width(Stream(s, 4), 8, 8);
  const Field cover = NoiseField(n, Fbm(Stream(s, 5), 3, 3, 3, 0.5, n));
  const double mm_px = 1e-3 / kSoilTileM * n;
  Crust c(n);
  ForEachTexel(c.mask, [&](int x, int y, double u, double v, double& m) {
    m = SmoothStep(-0.3, 0.3, cover.at(x, y));  // about half the ground crusted
    if (m <= 0.0) return;
    const double wu = u + 0.02 * warp_u(u, v);
    const double wv = v + 0.02 * warp_v(u, v);
    const double edge_px = polygons(wu, wv, 0.02).edge * n;
    const double half_px = 0.5 * (1.0 + 0.7 * width(u, v)) * mm_px;  // 0.5–1.5 mm wide
    c.crack.at(x, y) = m * Coverage(edge_px - half_px);
  });
  return c;
}

// A rounded aggregate, clod or grain of semi-axes a × b [px] along `d` at (cx, cy) [px]
// and reflectance `rho`, lit on the light's side, its shadow on the other.
void PaintAggregate(Field& f, double cx, double cy, double a, double b, const Eigen::Vector2d& d,
                    double rho, const Field& wobble) {
  auto radius = [&](double dx, double dy, int x, int y) {
    const double s = (dx * d.x() + dy * d.y()) / a;
    const double t = (-dx * d.y() + dy * d.x()) / b;
    const double w = 1.0 + 0.12 * std::min(2.0, std::max(-2.0, wobble.at(x, y)));
    return std::sqrt(s * s + t * t) / w;
  };
  const Eigen::Vector2d box = 1.3 * EllipseExtent(a, b, d) + Eigen::Vector2d(1.0, 1.0);
  const double shadow = 0.5 * b;
  ForEachInBox(f, cx - shadow * kLightX, cy - shadow * kLightY, box.x(), box.y(),
               [&](double& value, double dx, double dy, int x, int y) {
                 value *= 1.0 - 0.5 * Coverage((radius(dx, dy, x, y) - 1.0) * b);
               });
  ForEachInBox(f, cx, cy, box.x(), box.y(), [&](double& value, double dx, double dy, int x, int y) {
    const double r = radius(dx, dy, x, y);
    const double c = Coverage((r - 1.0) * b);
    if (c <= 0.0) return;
    const double slope = (dx * kLightX + dy * kLightY) / (std::max(a, b) + 0.5);
    const double lit = 0.75 + 0.5 * Clamp01(0.5 + 0.6 * slope * std::min(r, 1.0));
    value += c * (kSoilGrey * rho * lit - value);
  });
}

// The fine earth: its micro-relief lit, mottled, with the crust and its cracks.
void PaintEarth(Field& f, const Crust& crust, std::uint64_t s) {
  const int n = f.n;
  Field height(n);
  const Fbm lumps(Stream(s, 10), 8, 8, 4, 0.5, n);
  ForEachTexel(height, [&](int x, int y, double u, double v, double& h) {
    // 3 mm of lumps [tile]; the crust's plates stand 1 mm proud of their cracks.
    h = (3e-3 * lumps(u, v) + 1e-3 * crust.mask.at(x, y) * (1.0 - crust.crack.at(x, y))) /
        kSoilTileM;
  });
  const Field relief = Relief(height, kLightX, kLightY, kLightZ);
  const double flat = Lambert(0.0, 0.0, 1.0, kLightX, kLightY, kLightZ);
  const Field mottle = NoiseField(n, Fbm(Stream(s, 11), 4, 4, 3, 0.5, n));
  const std::uint64_t speckle = Stream(s, 12);
  ForEachTexel(f, [&](int x, int y, double, double, double& value) {
    const double rho = kEarthReflectance * (1.0 + 0.06 * mottle.at(x, y)) *
                       (1.0 + 0.05 * GaussFromBits(HashPoint(speckle, x, y))) *
                       (1.0 + 0.1 * crust.mask.at(x, y));
    const double lit = kSoilGrey * rho * std::max(0.0, 1.0 + relief.at(x, y) / flat);
    value = Lerp(lit, kSoilGrey * kSoilCrackReflectance, crust.crack.at(x, y));
  });
}

// Aggregates by structure class, clods, sand grains and straw, off the crust.
void PaintClods(Field& f, const Crust& crust, std::uint64_t s) {
  const int n = f.n;
  const double mm_px = 1e-3 / kSoilTileM * n;
  const Field wobble = NoiseField(n, Fbm(Stream(s, 20), 32, 32, 2, 0.5, n));
  Rng rng(Stream(s, 21));
  struct SizeClass {
    double lo_mm, hi_mm;
    int count;  // per 0.5 m tile, authored
  };
  // Medium, coarse and very coarse granules (USDA), clods; the largest last, on top.
  constexpr SizeClass kClasses[] = {
      {2.0, 5.0, 1800}, {5.0, 10.0, 300}, {10.0, 20.0, 40}, {20.0, 50.0, 6}};
  for (const SizeClass& sc : kClasses) {
    for (int k = 0; k < sc.count; ++k) {
      const double cx = rng.Uniform() * n;
      const double cy = rng.Uniform() * n;
      const double a = 0.5 * rng.Uniform(sc.lo_mm, sc.hi_mm) * mm_px;
      const double b = a * rng.Uniform(0.6, 1.0);
      const Eigen::Vector2d d = rng.Direction();
      const double rho = kEarthReflectance * (1.0 + 0.12 * rng.Gauss());
      const double crusted = crust.mask.at(static_cast<int>(cx), static_cast<int>(cy));
      if (rng.Uniform() < crusted) continue;  // the crust lies over them
      PaintAggregate(f, cx, cy, std::max(0.4, a), std::max(0.4, b), d, rho, wobble);
    }
  }
  constexpr int kSandGrains = 2000;  // coarse sand, authored
  for (int k = 0; k < kSandGrains; ++k) {
    const double cx = rng.Uniform() * n;
    const double cy = rng.Uniform() * n;
    const double r = std::max(0.35, 0.5 * rng.Uniform(0.5, 2.0) * mm_px);
    const double rho = rng.Uniform(0.55, 0.75);
    ForEachNear(f, cx, cy, r + 1.0, [&](double& value, double dx, double dy, int, int) {
      value += Coverage(std::sqrt(dx * dx + dy * dy) - r) * (kSoilGrey * rho - value);
    });
  }
  const int straws = 3 + static_cast<int>(rng.Uniform() * 6.0);
  for (int k = 0; k < straws; ++k) {
    const double px = rng.Uniform() * n;
    const Eigen::Vector2d p(px, rng.Uniform() * n);
    const Eigen::Vector2d d = rng.Direction();
    const double half = 0.5 * rng.Uniform(10.0, 40.0) * mm_px;
    const double w = 0.5 * rng.Uniform(1.0, 2.0) * mm_px;
    const double rho = rng.Chance(0.5) ? rng.Uniform(0.45, 0.6) : rng.Uniform(0.1, 0.2);
    const Eigen::Vector2d box = EllipseExtent(half + w, w, d);
    ForEachInBox(f, p.x(), p.y(), box.x() + 1.0, box.y() + 1.0,
                 [&](double& value, double dx, double dy, int, int) {
                   const double s_ = std::abs(dx * d.x() + dy * d.y()) - half;
                   const double t_ = std::abs(-dx * d.y() + dy * d.x()) - w;
                   const double c = Coverage(std::max(s_, t_));
                   value += c * (kSoilGrey * rho - value);
                 });
  }
}

}  // namespace

double SoilCrackShare(std::uint64_t seed, int variant, int size_px) {
  const std::uint64_t s = Mix(seed ^ HashName("sandy_loam"));
  const Crust c = MakeCrust(s, variant, size_px);
  double sum = 0.0;
  for (const double x : c.crack.v) sum += x;
  return sum / static_cast<double>(c.crack.v.size());
}

void SoilSurface(Field& f, std::uint64_t) {
  for (double& value : f.v) value = 0.0;
}

void SoilFeatures(Field& f, std::uint64_t seed, int variant) {
  const Crust crust = MakeCrust(seed, variant, f.n);
  const std::uint64_t s = SoilStream(seed, variant);
  PaintEarth(f, crust, s);
  PaintClods(f, crust, s);
}

}  // namespace trackbed::render
