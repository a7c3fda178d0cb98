// Dense asphalt concrete (see ground_asphalt.h). What it models and from where:
//
// - Coarse aggregate: SMA 11 S's grading (TL Asphalt-StB 07/13, Tabelle 8) as four
//   sieve classes; by Delesse's principle each class covers the share of the surface
//   that it takes of the mix's volume. A chip's face is an ellipse (long axis uniform
//   in its class, short over long 0.6–1: crushed, cubic chips, as SMA's flakiness limit
//   asks) painted smallest class first, larger chips over smaller ones.
// - Wear: traffic wears the binder film off the chips' tops (Pomerantz, Akbari & Harvey
//   2000, "Cooler reflective pavements give benefits beyond energy savings", LBNL: new
//   asphalt concrete has the binder's colour, about 0.05 reflectance, and lightens as
//   the aggregate shows): each face is stone-coloured within a share of its radius and
//   coated beyond it.
// - Tones: grey = 255 × reflectance (the textures' scale: grass, sand, soil have
//   about 255 × their material's albedo). Binder-rich mastic 0.05 (new asphalt, as
//   above) with its sand's speckle; stone 0.22 ± 0.04 (authored: a grey crushed rock).
//   The surface's mean reflectance comes out at about 0.09, a little under aged
//   asphalt's 0.10–0.15 (as above).
// - Per variant: hairline cracks 1–6 mm wide (low severity: under 6 mm, FHWA's LTPP
//   Distress Identification Manual, 2003) and drip stains; and one variant in four
//   each a crack sealed with a band of sealant, a saw-cut patch of newer mix, or a
//   fragment of a worn white marking 0.12 m wide (the narrow line of RMS, Richtlinien
//   für die Markierung von Straßen) whose paint reflects 0.40 (EN 1436's class B3 for
//   white markings). How many of each, their sizes beyond those and the wear are
//   authored.
//
// Bit-exact as procedural_texture.cpp: no floating-point contraction, no libm.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "ground_asphalt.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include "texture_blocks.h"

namespace trackbed::render {

using namespace texture_blocks;  // NOLINT: the recipes are written in its terms

namespace {

constexpr double kBinderReflectance = 0.05;  // new asphalt concrete (Pomerantz et al. 2000)
constexpr double kStoneReflectance = 0.22;   // authored: grey crushed rock
constexpr double kStoneSpread = 0.04;        // authored: chip to chip
constexpr double kCrackReflectance = 0.02;   // a shadowed gap (authored)
constexpr double kPaintReflectance = 0.40;   // EN 1436, class B3 (white)
constexpr double kGreyPerReflectance = 255.0;

// Mean of d² for d uniform in [lo, hi].
double MeanSquare(double lo, double hi) { return (lo * lo + lo * hi + hi * hi) / 3.0; }

// The quarter `q` (0–3) of the tile, as (u0, v0) of its corner [tile].
Eigen::Vector2d QuarterCorner(int q) { return Eigen::Vector2d(0.5 * (q % 2), 0.5 * (q / 2)); }

// A point uniform in quarter `q` at least `margin` [tile] from its edges.
Eigen::Vector2d InQuarter(Rng& rng, int q, double margin) {
  const Eigen::Vector2d c = QuarterCorner(q);
  const double x = rng.Uniform(margin, 0.5 - margin);
  const double y = rng.Uniform(margin, 0.5 - margin);
  return c + Eigen::Vector2d(x, y);
}

// Paints a chip's face: coated binder at its rim, stone inside, lit from the texture's
// light on its upper-left slope.
void PaintChip(Field& f, const AggregateChip& chip, const Field& wobble) {
  const int n = f.n;
  const double a = 0.5e-3 * chip.diameter_mm * n;  // semi-axes [px]
  const double b = a * chip.aspect;
  const Eigen::Vector2d d(chip.dir_x, chip.dir_y);
  const Eigen::Vector2d box = 1.15 * EllipseExtent(a, b, d) + Eigen::Vector2d(1.0, 1.0);
  const double stone = kGreyPerReflectance * chip.reflectance;
  const double binder = kGreyPerReflectance * kBinderReflectance;
  ForEachInBox(f, chip.x_m * n, chip.y_m * n, box.x(), box.y(),
               [&](double& value, double dx, double dy, int x, int y) {
                 const double s = (dx * d.x() + dy * d.y()) / a;
                 const double t = (-dx * d.y() + dy * d.x()) / b;
                 const double w = 1.0 + 0.08 * std::min(2.0, std::max(-2.0, wobble.at(x, y)));
                 const double r = std::sqrt(s * s + t * t) / w;
                 const double c = Coverage((r - 1.0) * b);
                 if (c <= 0.0) return;
                 const double clean = 1.0 - SmoothStep(chip.exposed - 0.15, chip.exposed, r);
                 const double slope = (dx * kLightX + dy * kLightY) / (a + 0.5);
                 const double lit = 0.85 + 0.3 * Clamp01(0.5 + 0.5 * slope * std::min(r, 1.0));
                 const double face = (binder + clean * (stone - binder)) * lit;
                 value += c * (face - value);
               });
}

// A crack: a wandering line of 1 cm steps, `length` [tile] at most and `width_px`
// wide, of grey `tone` (never lightening), kept inside quarter `q` clear of its edges.
void PaintCrack(Field& f, Rng& rng, int q, double length, double width_px, double tone) {
  const int n = f.n;
  const Eigen::Vector2d corner = QuarterCorner(q);
  Eigen::Vector2d p = InQuarter(rng, q, 0.08);
  Eigen::Vector2d dir = rng.Direction();
  constexpr double kStep = 0.01;  // [tile]
  const int steps = static_cast<int>(length / kStep);
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector2d turn = rng.Direction();
    dir = (dir + 0.35 * turn).normalized();
    const Eigen::Vector2d q1 = p + kStep * dir;
    const Eigen::Vector2d local = q1 - corner;
    const double margin = 0.02 + (0.5 * width_px + 1.0) / n;  // the line's half width and ramp
    if (local.minCoeff() < margin || local.maxCoeff() > 0.5 - margin) break;
    const Eigen::Vector2d a = p * n;
    const Eigen::Vector2d seg = (q1 - p) * n;
    const double len2 = seg.squaredNorm();
    const Eigen::Vector2d mid = 0.5 * (a + q1 * n);
    const double half = 0.5 * kStep * n + width_px + 1.0;
    ForEachNear(f, mid.x(), mid.y(), half, [&](double& value, double dx, double dy, int, int) {
      const Eigen::Vector2d rel = Eigen::Vector2d(dx, dy) + mid - a;
      const double t = Clamp01(rel.dot(seg) / len2);
      const double dist = (rel - t * seg).norm();
      const double c = Coverage(dist - 0.5 * width_px);
      value = std::min(value, value + c * (tone - value));
    });
    p = q1;
  }
}

// A soft blob of `radius` [tile] at `c` that scales the grey by `factor` at its centre.
void PaintStain(Field& f, const Eigen::Vector2d& c, double radius, double factor,
                const Field& edge) {
  const int n = f.n;
  const double r_px = radius * n;
  ForEachNear(f, c.x() * n, c.y() * n, 1.3 * r_px + 1.0,
              [&](double& value, double dx, double dy, int x, int y) {
                const double r = std::sqrt(dx * dx + dy * dy) / r_px + 0.15 * edge.at(x, y);
                const double w = 1.0 - SmoothStep(0.6, 1.0, r);
                value *= 1.0 - w * (1.0 - factor);
              });
}

// A worn marking: a rectangle `width` × `length` [tile] along `dir` whose paint is
// left where the wear noise allows, and on the chips' tops more than between them.
void PaintMarking(Field& f, const Eigen::Vector2d& c, const Eigen::Vector2d& dir, double width,
                  double length, const Field& wear) {
  const int n = f.n;
  const double hw = 0.5 * width * n;
  const double hl = 0.5 * length * n;
  const double paint = kGreyPerReflectance * kPaintReflectance;
  const Eigen::Vector2d box = EllipseExtent(hl, hw, dir) * 1.42 + Eigen::Vector2d(1.0, 1.0);
  ForEachInBox(f, c.x() * n, c.y() * n, box.x(), box.y(),
               [&](double& value, double dx, double dy, int x, int y) {
                 const double s = dx * dir.x() + dy * dir.y();
                 const double t = -dx * dir.y() + dy * dir.x();
                 const double inside = Coverage(std::abs(s) - hl) * Coverage(std::abs(t) - hw);
                 if (inside <= 0.0) return;
                 const double left = SmoothStep(-0.3, 0.3, wear.at(x, y));
                 value += inside * left * (paint - value);
               });
}

// A saw-cut patch of newer mix: darker (its binder not yet worn off), with a sealed
// seam along its edges.
void PaintPatch(Field& f, const Eigen::Vector2d& c, double hu, double hv) {
  const int n = f.n;
  const double seam_px = std::max(0.5, 0.006 * n);
  const double binder = kGreyPerReflectance * kBinderReflectance;
  ForEachInBox(f, c.x() * n, c.y() * n, hu * n + seam_px + 1.0, hv * n + seam_px + 1.0,
               [&](double& value, double dx, double dy, int, int) {
                 const double ex = std::abs(dx) - hu * n;
                 const double ey = std::abs(dy) - hv * n;
                 const double inside = Coverage(ex) * Coverage(ey);
                 const double newer = binder + 0.45 * (value - binder);
                 value += inside * (newer - value);
                 const double seam = Coverage(std::abs(std::max(ex, ey)) - seam_px);
                 value += seam * (0.8 * binder - value);
               });
}

}  // namespace

double AggregateVolumeShare() {
  constexpr double kBinderMass = 0.066;
  constexpr double kRockDensity = 2.65;
  constexpr double kBinderDensity = 1.03;
  constexpr double kVoids = 0.03;
  const double rock = (1.0 - kBinderMass) / kRockDensity;
  const double binder = kBinderMass / kBinderDensity;
  return rock * (1.0 - kVoids) / (rock + binder);
}

std::vector<AggregateChip> AsphaltAggregate(std::uint64_t seed) {
  std::vector<AggregateChip> chips;
  const double volume = AggregateVolumeShare();
  constexpr double kMeanAspect = 0.8;  // aspect uniform in [0.6, 1]
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < static_cast<int>(std::size(kSma11Coarse)); ++k) {
    const SieveClass& sc = kSma11Coarse[k];
    const double area_share = volume * sc.mass_share;  // of the 1 m² tile
    const double face_m2 = 0.25 * kPi * MeanSquare(sc.lo_mm, sc.hi_mm) * 1e-6 * kMeanAspect;
    const int count = static_cast<int>(area_share / face_m2 + 0.5);
    Rng rng(Stream(seed, static_cast<std::uint64_t>(k)));
    for (int i = 0; i < count; ++i) {
      AggregateChip c;
      c.x_m = rng.Uniform();
      c.y_m = rng.Uniform();
      c.diameter_mm = rng.Uniform(sc.lo_mm, sc.hi_mm);
      c.aspect = rng.Uniform(0.6, 1.0);
      const Eigen::Vector2d d = rng.Direction();
      c.dir_x = d.x();
      c.dir_y = d.y();
      c.reflectance = kStoneReflectance + kStoneSpread * rng.Gauss();
      c.exposed = rng.Uniform(0.5, 0.9);
      c.sieve_class = k;
      chips.push_back(c);
    }
  }
  return chips;
}

void AsphaltSurface(Field& f, std::uint64_t seed) {
  const int n = f.n;
  // The mastic: binder with its sand (under 2 mm, below a texel at 256 px a metre) as a
  // speckle of up to 60 % more light, and binder-rich and lean areas (authored ±10 %).
  const Field rich = NoiseField(n, Fbm(Stream(seed, 10), 4, 4, 4, 0.5, n));
  ForEachTexel(f, [&](int x, int y, double, double, double& value) {
    const double sand = UnitFromBits(HashPoint(Stream(seed, 11), x, y));
    value = kGreyPerReflectance * kBinderReflectance * (1.0 + 0.6 * sand) *
            (1.0 + 0.1 * std::min(2.0, std::max(-2.0, rich.at(x, y))));
  });
  const Field wobble = NoiseField(n, Fbm(Stream(seed, 12), 64, 64, 1, 0.5, n));
  for (const AggregateChip& chip : AsphaltAggregate(Stream(seed, 13))) PaintChip(f, chip, wobble);
}

void AsphaltFeatures(Field& f, std::uint64_t seed, int variant) {
  const int n = f.n;
  const std::uint64_t s = Stream(seed, 100 + static_cast<std::uint64_t>(variant));
  Rng rng(Stream(s, 0));
  const Field edge = NoiseField(n, Fbm(Stream(s, 1), 16, 16, 2, 0.5, n));
  const Field wear = NoiseField(n, Fbm(Stream(s, 2), 32, 32, 2, 0.6, n));
  // Quarters in a seeded order, so that features of one variant do not overlap.
  int order[4] = {0, 1, 2, 3};
  for (int i = 3; i > 0; --i) std::swap(order[i], order[static_cast<int>(rng.Uniform() * (i + 1))]);
  const double texel = 1.0 / n;
  const int cracks = 1 + static_cast<int>(rng.Uniform() * 2.0);
  for (int k = 0; k < cracks; ++k) {
    const double width_px = std::max(0.35, rng.Uniform(0.001, 0.006) / texel);
    PaintCrack(f, rng, order[0], rng.Uniform(0.1, 0.35), width_px,
               kGreyPerReflectance * kCrackReflectance);
  }
  const int stains = 1 + static_cast<int>(rng.Uniform() * 3.0);
  for (int k = 0; k < stains; ++k) {
    const double radius = rng.Uniform(0.03, 0.1);
    const Eigen::Vector2d c = InQuarter(rng, order[2], radius * 1.3 + 0.03);
    PaintStain(f, c, radius, rng.Uniform(0.55, 0.8), edge);
  }
  // One rarer feature per variant, in turn: none, a crack sealed under a band of binder
  // 4–8 cm wide, a patch, a worn marking (each on a quarter of the tiles).
  const Eigen::Vector2d centre = QuarterCorner(order[3]) + Eigen::Vector2d(0.25, 0.25);
  if (variant % 4 == 1) {
    // One draw a statement (a call's arguments are evaluated in the compiler's order),
    // the width first, as the pinned bytes have it; the same for the patch's sides.
    const double width_m = rng.Uniform(0.04, 0.08);
    const double length = rng.Uniform(0.15, 0.35);
    PaintCrack(f, rng, order[1], length, width_m / texel, kGreyPerReflectance * 0.04);
  } else if (variant % 4 == 2) {
    const double half_v = rng.Uniform(0.07, 0.17);
    const double half_u = rng.Uniform(0.07, 0.17);
    PaintPatch(f, centre, half_u, half_v);
  } else if (variant % 4 == 3) {
    const double length = rng.Uniform(0.15, 0.35);
    PaintMarking(f, centre, rng.Direction(), 0.12, length, wear);
  }
}

}  // namespace trackbed::render
