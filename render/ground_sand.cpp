// Dry wind-rippled sand (see ground_sand.h). What it models and from where:
//
// - Impact ripples: crests across the wind of wavelength 6–12.5 cm and ripple index
//   (wavelength over height) 30–70, the range a dictionary of the earth sciences gives
//   for wind ripples (Allaby, Oxford Dictionary of Earth Sciences, "ripple index": wind
//   ripples 30–70, heights up to about 1 cm; Bagnold 1941, The Physics of Blown Sand and
//   Desert Dunes, ch. 10, and Sharp 1963, J. Geol. 71, describe the ripples of dune sand
//   at a few to about 15 cm). The profile is asymmetric: a long stoss slope, the crest at
//   70 % of the wavelength, a short lee (authored share). Real ripple fields are not
//   straight: their crests meander, fork at Y-junctions and end (Yizhaq, Balmforth &
//   Provenzale 2004, Physica D 195: bifurcations and defects of desert ripples). Here a
//   junction is a phase dislocation, a crest that ends is a pair of them or a patch where
//   the ripples fade; their counts are authored.
// - The sand's grains: medium sand (ISO 14688-1, 0.2–0.63 mm; Wentworth 1922,
//   0.25–0.5 mm) lies below a 2 mm texel, about 30 grains to a texel, so it shows as a
//   speckle of the grains' mean (authored spread 4 %).
// - Coarse grains on the crests: coarse sand (ISO 14688-1, 0.63–2 mm) and granules (2–4
//   mm, Wentworth; ISO's fine gravel 2–6.3 mm) collect at ripple crests, too heavy to
//   saltate (Bagnold 1941; Sharp 1963); here placed by the crest's height.
// - Pebbles (ISO medium gravel, 6.3–20 mm), shell fragments and twigs: a few per tile,
//   authored counts.
// - Tones: grey = 255 × reflectance, the sand at `dry_sand`'s albedo 0.68
//   (sim/terrain_material.cpp), lit by the textures' light.
//
// Variants agree at the tile's edges and differ inside: within 2 % of a tile of an edge
// a variant is the shared field only, and from 16 % on it is its own; tiles of equal shift
// meet with their crests continuous (the tiling's shifts are free: docs/rendering.md).
//
// Bit-exact as procedural_texture.cpp: no floating-point contraction, no libm.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "ground_sand.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "texture_blocks.h"

namespace trackbed::render {

using namespace texture_blocks;  // NOLINT: the recipes are written in its terms

namespace {

constexpr double kSandReflectance = 0.68;  // dry_sand's albedo (sim/terrain_material.cpp)
constexpr double kSandGrey = 255.0;
constexpr double kSandPi = 3.14159265358979323846;
constexpr double kSandCrest = 0.7;      // the crest's place in a wavelength (authored)
constexpr double kSandEdgeZero = 0.02;  // [tile] variants are the shared field here
constexpr double kSandEdgeOwn = 0.16;   // [tile] and their own from here on

// atan(x) for |x| ≤ 1: a minimax polynomial, error under 2e-5 rad.
double SandAtanUnit(double x) {
  const double x2 = x * x;
  return x *
         (0.9998660 + x2 * (-0.3302995 + x2 * (0.1801410 + x2 * (-0.0851330 + x2 * 0.0208351))));
}

// The angle of (x, y) in (−π, π], its cut along the negative x axis.
double SandAngle(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  if (ax == 0.0 && ay == 0.0) return 0.0;
  double a = ax >= ay ? SandAtanUnit(ay / ax) : 0.5 * kSandPi - SandAtanUnit(ax / ay);
  if (x < 0.0) a = kSandPi - a;
  return y < 0.0 ? -a : a;
}

// The asymmetric ripple profile of period 1: 0 in the trough, 1 on the crest.
double SandProfile(double t) {
  const double f = t - std::floor(t);
  return f < kSandCrest ? SmoothStep(0.0, kSandCrest, f) : 1.0 - SmoothStep(kSandCrest, 1.0, f);
}

// 0 within kSandEdgeZero of the tile's edges, 1 beyond kSandEdgeOwn.
double SandOwnWeight(double u, double v) {
  auto side = [](double t) {
    return SmoothStep(kSandEdgeZero, kSandEdgeOwn, std::min(t, 1.0 - t));
  };
  return side(u) * side(v);
}

// A pair of opposite phase dislocations: crests fork at one and rejoin at the other.
struct Dislocation {
  double au = 0.0, av = 0.0, bu = 0.0, bv = 0.0;
};

// The ripple phase and amplitude of one variant at any point of the tile.
class SandPhase {
 public:
  SandPhase(std::uint64_t seed, int variant, int n)
      : field_(SandRipples(seed)),
        meander_(Stream(seed, 1), 2, 2, 3, 0.5, n),
        own_(Stream(Stream(seed, 10 + static_cast<std::uint64_t>(variant)), 0), 3, 3, 2, 0.5, n),
        fade_(Stream(Stream(seed, 10 + static_cast<std::uint64_t>(variant)), 1), 4, 4, 2, 0.5, n) {
    Rng rng(Stream(Stream(seed, 10 + static_cast<std::uint64_t>(variant)), 2));
    const int pairs = 1 + static_cast<int>(rng.Uniform() * 3.0);  // 1–3, authored
    const double wavelength_tile = field_.wavelength_m / kSandTileM;
    for (int k = 0; k < pairs; ++k) {
      Dislocation d;
      d.au = rng.Uniform(0.25, 0.75);
      d.av = rng.Uniform(0.25, 0.75);
      const Eigen::Vector2d dir = rng.Direction();
      const double length = rng.Uniform(1.0, 3.0) * wavelength_tile;
      d.bu = std::min(0.8, std::max(0.2, d.au + length * dir.x()));
      d.bv = std::min(0.8, std::max(0.2, d.av + length * dir.y()));
      pairs_.push_back(d);
    }
  }

  // The phase [wavelengths] at (u, v).
  double Phase(double u, double v) const {
    double own = 0.4 * own_(u, v);
    for (const Dislocation& d : pairs_) {
      // arg((p − a) / (p − b)): the two dislocations' angles' difference, its cut only on
      // the segment between them (where the phase steps by a whole wavelength).
      const double ax = u - d.au, ay = v - d.av, bx = u - d.bu, by = v - d.bv;
      own += SandAngle(ay * bx - ax * by, ax * bx + ay * by) / (2.0 * kSandPi);
    }
    return field_.kx * u + field_.ky * v + 0.35 * meander_(u, v) + SandOwnWeight(u, v) * own;
  }

  // The ripples' amplitude [0, 1] at (u, v): where it falls, crests end.
  double Amplitude(double u, double v) const {
    return 1.0 - SandOwnWeight(u, v) * 0.9 * SmoothStep(0.15, 0.4, fade_(u, v));
  }

  // Height of the crest above the trough's level at (u, v), [0, 1].
  double Crest(double u, double v) const { return Amplitude(u, v) * SandProfile(Phase(u, v)); }

  const RippleField& field() const { return field_; }

 private:
  RippleField field_;
  Fbm meander_;
  Fbm own_;
  Fbm fade_;
  std::vector<Dislocation> pairs_;
};

// A rounded grain or pebble of `radius` [px] and reflectance `rho` at (cx, cy) [px],
// lit on the light's side, with its shadow on the other.
void PaintSandGrain(Field& f, double cx, double cy, double radius, double rho) {
  const double shadow = 0.4 * radius;
  ForEachNear(f, cx - shadow * kLightX, cy - shadow * kLightY, radius + 1.0,
              [&](double& value, double dx, double dy, int, int) {
                value *= 1.0 - 0.45 * Coverage(std::sqrt(dx * dx + dy * dy) - radius);
              });
  ForEachNear(f, cx, cy, radius + 1.0, [&](double& value, double dx, double dy, int, int) {
    const double r = std::sqrt(dx * dx + dy * dy);
    const double c = Coverage(r - radius);
    if (c <= 0.0) return;
    const double lit = Clamp01(0.65 + 0.45 * (dx * kLightX + dy * kLightY) / (radius + 0.5));
    value += c * (kSandGrey * rho * (0.55 + 0.6 * lit) - value);
  });
}

// A curved stroke (a shell's arc or a twig): the arc of `radius` [px] around (cx, cy)
// from angle-direction `from` over `sweep` of a turn, `width` [px] wide.
void PaintSandArc(Field& f, double cx, double cy, double radius, const Eigen::Vector2d& from,
                  double sweep, double width, double rho) {
  const int steps = std::max(2, static_cast<int>(sweep * 2.0 * kSandPi * radius / 1.5));
  // The rotation of one step: cos and sin of a small angle from their Taylor series
  // (no libm), renormalised at each step.
  const double step_len = sweep * 2.0 * kSandPi / steps;  // [rad]
  const double c1 =
      1.0 - 0.5 * step_len * step_len + step_len * step_len * step_len * step_len / 24.0;
  const double s1 = step_len - step_len * step_len * step_len / 6.0;
  Eigen::Vector2d d = from;
  for (int k = 0; k <= steps; ++k) {
    const double px = cx + radius * d.x();
    const double py = cy + radius * d.y();
    ForEachNear(f, px, py, 0.5 * width + 1.0, [&](double& value, double dx, double dy, int, int) {
      const double c = Coverage(std::sqrt(dx * dx + dy * dy) - 0.5 * width);
      value += c * (kSandGrey * rho - value);
    });
    d = Eigen::Vector2d(c1 * d.x() - s1 * d.y(), s1 * d.x() + c1 * d.y()).normalized();
  }
}

// The ripples' grey: the height field lit by the textures' light over the grains' speckle.
void PaintRipples(Field& f, const SandPhase& phase, std::uint64_t seed) {
  const int n = f.n;
  const double height_tile = phase.field().height_m / kSandTileM;
  Field height(n);
  ForEachTexel(height, [&](int, int, double u, double v, double& h) {
    h = height_tile * phase.Crest(u, v);
  });
  const Field relief = Relief(height, kLightX, kLightY, kLightZ);
  const double flat = Lambert(0.0, 0.0, 1.0, kLightX, kLightY, kLightZ);
  const std::uint64_t speckle = Stream(seed, 3);  // shared by the variants
  ForEachTexel(f, [&](int x, int y, double, double, double& value) {
    const double grains = 1.0 + 0.04 * GaussFromBits(HashPoint(speckle, x, y));
    value = kSandGrey * kSandReflectance * grains * (1.0 + relief.at(x, y) / flat);
  });
}

// A point of the tile at least `margin` [tile] from its edges.
Eigen::Vector2d SandInside(Rng& rng, double margin) {
  const double u = rng.Uniform(margin, 1.0 - margin);
  const double v = rng.Uniform(margin, 1.0 - margin);
  return Eigen::Vector2d(u, v);
}

// Coarse sand and granules, most of them on the crests.
void PaintCrestGrains(Field& f, const SandPhase& phase, Rng& rng) {
  const int n = f.n;
  const double mm_px = 1e-3 / kSandTileM * n;  // texels per mm
  constexpr int kCoarse = 2500;                // per tile, authored
  constexpr int kGranules = 250;
  for (int k = 0; k < kCoarse + kGranules; ++k) {
    const bool granule = k >= kCoarse;
    const double d_mm = granule ? rng.Uniform(2.0, 4.0) : rng.Uniform(0.63, 2.0);
    const Eigen::Vector2d p = SandInside(rng, kSandEdgeZero + 0.5 * d_mm * mm_px / n + 2.0 / n);
    const double crest = phase.Crest(p.x(), p.y());
    const double keep = rng.Uniform();
    if (keep > 0.05 + 0.95 * crest * crest * crest * crest) continue;
    const double rho = rng.Uniform(0.25, 0.85);  // quartz, feldspar, lithic and dark grains
    PaintSandGrain(f, p.x() * n, p.y() * n, std::max(0.35, 0.5 * d_mm * mm_px), rho);
  }
}

// Pebbles, shell fragments and twigs of one variant.
void PaintSandDebris(Field& f, Rng& rng) {
  const int n = f.n;
  const double mm_px = 1e-3 / kSandTileM * n;
  const int pebbles = static_cast<int>(rng.Uniform() * 3.0);  // 0–2, authored
  for (int k = 0; k < pebbles; ++k) {
    const double d_mm = rng.Uniform(6.3, 20.0);
    const Eigen::Vector2d p = SandInside(rng, kSandEdgeZero + d_mm * mm_px / n + 2.0 / n);
    PaintSandGrain(f, p.x() * n, p.y() * n, 0.5 * d_mm * mm_px, rng.Uniform(0.25, 0.6));
  }
  const int shells = static_cast<int>(rng.Uniform() * 3.0);  // 0–2
  for (int k = 0; k < shells; ++k) {
    const double radius_mm = rng.Uniform(5.0, 12.0);
    const Eigen::Vector2d p = SandInside(rng, kSandEdgeZero + 2.0 * radius_mm * mm_px / n + 0.01);
    const Eigen::Vector2d from = rng.Direction();
    const double sweep = rng.Uniform(0.15, 0.4);  // of a turn
    const double width = rng.Uniform(1.5, 3.0) * mm_px;
    PaintSandArc(f, p.x() * n, p.y() * n, radius_mm * mm_px, from, sweep, width, 0.85);
  }
  const int twigs = static_cast<int>(rng.Uniform() * 2.0);  // 0–1
  for (int k = 0; k < twigs; ++k) {
    const double half_mm = 0.5 * rng.Uniform(40.0, 120.0);
    const Eigen::Vector2d mid = SandInside(rng, kSandEdgeZero + (half_mm + 5.0) * mm_px / n);
    const Eigen::Vector2d dir = rng.Direction();
    const Eigen::Vector2d across(-dir.y(), dir.x());
    const double bow_mm = rng.Uniform(-0.1, 0.1) * half_mm;  // a gently bent stick
    const double width = rng.Uniform(2.0, 4.0) * mm_px;
    const double rho = rng.Uniform(0.15, 0.25);
    const int steps = std::max(2, static_cast<int>(2.0 * half_mm * mm_px / 0.75));
    for (int s = 0; s <= steps; ++s) {
      const double t = -1.0 + 2.0 * s / steps;
      const Eigen::Vector2d q =
          mid * n + (t * half_mm * dir + bow_mm * (1.0 - t * t) * across) * mm_px;
      ForEachNear(f, q.x(), q.y(), 0.5 * width + 1.0,
                  [&](double& value, double dx, double dy, int, int) {
                    const double c = Coverage(std::sqrt(dx * dx + dy * dy) - 0.5 * width);
                    value += c * (kSandGrey * rho - value);
                  });
    }
  }
}

}  // namespace

RippleField SandRipples(std::uint64_t seed) {
  Rng rng(Stream(seed, 0));
  RippleField r;
  // Integer wave numbers keep the field periodic over the tile; |k| from 4 to 8 per 0.5 m
  // gives wavelengths of 6.2–12.5 cm, the wind across the v axis within ±14°.
  r.ky = 4 + static_cast<int>(rng.Uniform() * 5.0);
  r.kx = static_cast<int>(rng.Uniform() * 3.0) - 1;
  r.wavelength_m = kSandTileM / std::sqrt(static_cast<double>(r.kx * r.kx + r.ky * r.ky));
  r.height_m = r.wavelength_m / rng.Uniform(kRippleIndexMin, kRippleIndexMax);
  return r;
}

void SandSurface(Field& f, std::uint64_t) {
  for (double& value : f.v) value = kSandGrey * kSandReflectance;
}

void SandFeatures(Field& f, std::uint64_t seed, int variant) {
  const SandPhase phase(seed, variant, f.n);
  PaintRipples(f, phase, seed);
  Rng rng(Stream(Stream(seed, 10 + static_cast<std::uint64_t>(variant)), 3));
  PaintCrestGrains(f, phase, rng);
  PaintSandDebris(f, rng);
}

}  // namespace trackbed::render
