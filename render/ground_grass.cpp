// A mown lawn (see ground_grass.h). What it models and from where:
//
// - The sward: Kentucky bluegrass (Poa pratensis), the common lawn grass, mown at about
//   5 cm. Leaf blades 2–4 mm wide (its fine-to-medium leaf texture; Brede & Duich 1982,
//   Agron. J. 74: 865, measured leaf widths, angles and densities of Kentucky bluegrass
//   turf); 3–4 green leaves per shoot (Duble, Texas Cooperative Extension, "Kentucky
//   bluegrass"); 150 shoots per dm², an authored lawn density under the densest turf's
//   (bentgrass greens, over 1 700 per dm²). Shoots stand in tufts of 3–8 tillers within
//   1 cm (tillering; authored). Seen from above a blade shows its length times the sine
//   of its angle from the vertical: 25–85 % of 3–8 cm (authored).
// - A blade's light: folded along its midrib (a V of ±25°, authored), each half lit by
//   the textures' light on its own, lighter toward the tip as it bends over; mown tips
//   brown over the last 1–2 mm (a cut leaf's tip dies back). Deeper blades receive less
//   light: Beer–Lambert extinction through the leaf area above them (Monsi & Saeki 1953),
//   extinction coefficient 0.5 (a spherical leaf-angle distribution).
// - Under the canopy: thatch (dead blades, lighter and browner) and soil in the gaps,
//   half lit (authored). Tones: green leaf 0.10, thatch 0.25, moist soil 0.12 visible
//   reflectance (typical luminance of green vegetation, litter and dark soil); the tile's
//   mean is scaled to 255 × `grass`'s albedo 0.38 (sim/terrain_material.cpp), the scale of
//   every ground texture.
//
// Bit-exact as procedural_texture.cpp: no floating-point contraction, no libm.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "ground_grass.h"

#include <algorithm>
#include <cmath>

#include "texture_blocks.h"

namespace trackbed::render {

using namespace texture_blocks;  // NOLINT: the recipes are written in its terms

namespace {

constexpr double kLeafReflectance = 0.10;
constexpr double kThatchReflectance = 0.25;
constexpr double kLawnSoilReflectance = 0.12;
constexpr double kGrassAlbedo = 0.38;  // grass's albedo (sim/terrain_material.cpp)
constexpr double kExtinction = 0.5;    // Monsi & Saeki: spherical leaf angles
constexpr double kFoldSin = 0.4226;    // sin 25°
constexpr double kFoldCos = 0.9063;    // cos 25°

// e^(−x) for x ≥ 0 as (1 − x/256)^256: eight squarings, within 1 % for x ≤ 4.
double LawnExpNeg(double x) {
  double y = std::max(0.0, 1.0 - x / 256.0);
  for (int k = 0; k < 8; ++k) y *= y;
  return y;
}

// Scales the field so that its mean is `mean`.
void ScaleMean(Field& f, double mean) {
  double sum = 0.0;
  for (const double x : f.v) sum += x;
  const double m = sum / static_cast<double>(f.v.size());
  if (m <= 0.0) return;
  for (double& x : f.v) x *= mean / m;
}

// Paints one blade: a strap tapering to a boat-shaped tip, its two halves lit apart.
void PaintBlade(Field& f, const GrassBlade& b, double light, double reflectance) {
  const int n = f.n;
  const double len = b.length * n;
  const double half_w = 0.5 * b.width_mm * 1e-3 / kGrassTileM * n;
  const Eigen::Vector2d d(b.dir_x, b.dir_y);
  const Eigen::Vector2d across(-d.y(), d.x());
  const Eigen::Vector2d mid = Eigen::Vector2d(b.x, b.y) * n + 0.5 * len * d;
  const Eigen::Vector2d box = EllipseExtent(0.5 * len + half_w, half_w, d);
  // Each half's normal, folded about the midrib: lit apart by the textures' light.
  const double flat = Lambert(0.0, 0.0, 1.0, kLightX, kLightY, kLightZ);
  const double left =
      Lambert(kFoldSin * across.x(), kFoldSin * across.y(), kFoldCos, kLightX, kLightY, kLightZ) /
      flat;
  const double right =
      Lambert(-kFoldSin * across.x(), -kFoldSin * across.y(), kFoldCos, kLightX, kLightY, kLightZ) /
      flat;
  const double tip_px = 1.5e-3 / kGrassTileM * n;  // the mown tip's brown end
  ForEachInBox(f, mid.x(), mid.y(), box.x() + 1.0, box.y() + 1.0,
               [&](double& value, double dx, double dy, int, int) {
                 const double perp = dx * across.x() + dy * across.y();
                 if (std::abs(perp) >= half_w + 0.5) return;
                 const double along = dx * d.x() + dy * d.y() + 0.5 * len;
                 const double t = Clamp01(along / len);
                 const double beyond = along - t * len;
                 const double taper = t < 0.85 ? 1.0 : 1.0 - 0.8 * (t - 0.85) / 0.15;
                 const double c =
                     Coverage(std::sqrt(perp * perp + beyond * beyond) - half_w * taper);
                 if (c <= 0.0) return;
                 const double side = perp > 0.0 ? left : right;
                 const double bend = 0.85 + 0.3 * t;  // the blade leans over toward its tip
                 const bool dead = len - along < tip_px;
                 const double rho = dead ? kThatchReflectance : reflectance * b.tone;
                 value += c * (255.0 * rho * std::max(0.0, side) * bend * light - value);
               });
}

}  // namespace

std::vector<GrassBlade> GrassSward(std::uint64_t seed, int variant) {
  Rng rng(Stream(Stream(seed, 20 + static_cast<std::uint64_t>(variant)), 0));
  const double area_dm2 = kGrassTileM * kGrassTileM * 100.0;
  const int shoots = static_cast<int>(kShootsPerDm2 * area_dm2 + 0.5);
  std::vector<GrassBlade> blades;
  int placed = 0;
  while (placed < shoots) {
    // A tuft of tillers around its crown.
    const double cx = rng.Uniform();
    const double cy = rng.Uniform();
    const int tillers = std::min(shoots - placed, 3 + static_cast<int>(rng.Uniform() * 6.0));
    for (int s = 0; s < tillers; ++s, ++placed) {
      const Eigen::Vector2d around = rng.Direction();
      const Eigen::Vector2d off = around * rng.Uniform(0.0, 0.01 / kGrassTileM);
      const int leaves =
          kLeavesPerShootMin +
          static_cast<int>(rng.Uniform() * (kLeavesPerShootMax - kLeavesPerShootMin + 1));
      for (int l = 0; l < leaves; ++l) {
        GrassBlade b;
        b.x = cx + off.x();
        b.y = cy + off.y();
        const Eigen::Vector2d d = rng.Direction();
        b.dir_x = d.x();
        b.dir_y = d.y();
        const double leaf_m = rng.Uniform(0.03, 0.08);
        b.length = leaf_m * rng.Uniform(0.25, 0.85) / kGrassTileM;  // × sin of its angle
        b.width_mm = rng.Uniform(kBladeWidthMinMm, kBladeWidthMaxMm);
        b.tone = 1.0 + 0.15 * rng.Gauss();
        b.depth = rng.Uniform();
        blades.push_back(b);
      }
    }
  }
  std::sort(blades.begin(), blades.end(),
            [](const GrassBlade& a, const GrassBlade& b) { return a.depth < b.depth; });
  return blades;
}

void GrassSurface(Field& f, std::uint64_t) {
  for (double& value : f.v) value = 0.0;
}

void GrassFeatures(Field& f, std::uint64_t seed, int variant) {
  const int n = f.n;
  const std::uint64_t s = Stream(seed, 20 + static_cast<std::uint64_t>(variant));
  // Soil with thatch over it, half lit in the gaps.
  const Field mottle = NoiseField(n, Fbm(Stream(s, 1), 8, 8, 3, 0.5, n));
  ForEachTexel(f, [&](int x, int y, double, double, double& value) {
    value =
        0.5 * 255.0 * kLawnSoilReflectance * (1.0 + 0.2 * Clamp01(0.5 + 0.25 * mottle.at(x, y)));
  });
  Rng rng(Stream(s, 2));
  constexpr int kThatch = 1500;  // dead blades per tile, authored
  for (int k = 0; k < kThatch; ++k) {
    GrassBlade b;
    b.x = rng.Uniform();
    b.y = rng.Uniform();
    const Eigen::Vector2d d = rng.Direction();
    b.dir_x = d.x();
    b.dir_y = d.y();
    b.length = rng.Uniform(0.01, 0.04) / kGrassTileM;
    b.width_mm = rng.Uniform(1.0, 2.5);
    b.tone = 1.0 + 0.2 * rng.Gauss();
    PaintBlade(f, b, 0.5, kThatchReflectance);
  }
  // The sward, bottom first: the leaf area above a blade dims it.
  const std::vector<GrassBlade> blades = GrassSward(seed, variant);
  double area = 0.0;  // the blades' projected area [tile²]
  for (const GrassBlade& b : blades) area += 0.9 * b.length * b.width_mm * 1e-3 / kGrassTileM;
  for (const GrassBlade& b : blades) {
    PaintBlade(f, b, LawnExpNeg(kExtinction * area * (1.0 - b.depth)), kLeafReflectance);
  }
  ScaleMean(f, 255.0 * kGrassAlbedo);
}

}  // namespace trackbed::render
