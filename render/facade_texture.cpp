// A rendered house front (see facade_texture.h). What it models and from where:
//
// - Layout: storeys of kFacadeStoreyM and bays of kFacadeBayM, each bay one window
//   opening of kFacadeWindowWidthM × kFacadeWindowHeightM whose sill sits
//   kFacadeSillHeightM above the storey's floor (the header names the sources).
// - A window: a white PVC frame, two casements with a mullion between them, each pane
//   inset by kFacadeFrameM; glass that reflects the street and a sky darker than the
//   open one, darker towards its foot (authored: 0.20-0.35 reflectance); in half the
//   windows a roller shutter (the German Rollladen) lowered part-way, slats of 50 mm.
// - Relief painted in: the opening is recessed, so its top and one side reveal lie in
//   shadow under a high sun; an aluminium sill below it with its own shadow, and faint
//   rain streaks running down from its ends.
// - The wall: a mineral plaster (reflectance 0.67, authored: a light render) mottled by
//   weathering, with a fine grain.
//
// Bit-exact as procedural_texture.cpp: no floating-point contraction, no libm.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "facade_texture.h"

#include <algorithm>
#include <cmath>

#include "texture_blocks.h"

namespace trackbed::render {

using namespace texture_blocks;  // NOLINT: the recipe is written in its terms

namespace {

// Blends the rectangle [a0, a1] × [h0, h1] (metres along the tile and up it) towards
// `tone` by `opacity`, antialiased at its edges.
void FillRect(Field& f, double a0, double h0, double a1, double h1, double tone,
              double opacity = 1.0) {
  const double px = f.n / kFacadeTileM;
  const double hx = 0.5 * (a1 - a0) * px, hy = 0.5 * (h1 - h0) * px;
  ForEachInBox(f, 0.5 * (a0 + a1) * px, 0.5 * (h0 + h1) * px, hx + 1.0, hy + 1.0,
               [&](double& value, double dx, double dy, int, int) {
                 const double c =
                     Coverage(std::abs(dx) - hx) * Coverage(std::abs(dy) - hy) * opacity;
                 value += c * (tone - value);
               });
}

// Scales the rectangle's grey levels by `factor` (a shadow), antialiased at its edges.
void ShadeRect(Field& f, double a0, double h0, double a1, double h1, double factor) {
  const double px = f.n / kFacadeTileM;
  const double hx = 0.5 * (a1 - a0) * px, hy = 0.5 * (h1 - h0) * px;
  ForEachInBox(f, 0.5 * (a0 + a1) * px, 0.5 * (h0 + h1) * px, hx + 1.0, hy + 1.0,
               [&](double& value, double dx, double dy, int, int) {
                 const double c = Coverage(std::abs(dx) - hx) * Coverage(std::abs(dy) - hy);
                 value *= 1.0 - c * (1.0 - factor);
               });
}

// One window whose opening's lower left corner is at (a, h) [m].
void Window(Field& f, double a, double h, Rng& rng) {
  constexpr double W = kFacadeWindowWidthM, H = kFacadeWindowHeightM, F = kFacadeFrameM;
  constexpr double kFrameTone = 214.0;
  // The sill: 30 mm of aluminium below the opening, 30 mm wider each side; its shadow.
  ShadeRect(f, a - 0.03, h - 0.08, a + W + 0.03, h - 0.03, 0.72);
  FillRect(f, a - 0.03, h - 0.03, a + W + 0.03, h, 196.0);
  // Rain streaks from the sill's ends.
  for (const double end : {a - 0.01, a + W - 0.04}) {
    const double length = rng.Uniform(0.3, 0.9);
    const double depth = rng.Uniform(0.88, 0.96);
    for (int k = 0; k < 4; ++k) {
      const double top = h - 0.08 - length * k / 4.0;
      ShadeRect(f, end, top - length / 4.0, end + 0.05, top, depth + (1.0 - depth) * k / 4.0);
    }
  }
  FillRect(f, a, h, a + W, h + H, kFrameTone);
  // Two panes; glass darker towards its foot, each window its own tone.
  const double glass = rng.Uniform(48.0, 72.0);
  const double half = 0.5 * W;
  for (const double p : {a, a + half}) {
    const double x0 = p + (p == a ? F : 0.5 * F), x1 = p + half - (p == a ? 0.5 * F : F);
    constexpr int kSteps = 6;
    for (int k = 0; k < kSteps; ++k) {
      const double z0 = h + F + (H - 2 * F) * k / kSteps;
      FillRect(f, x0, z0, x1, z0 + (H - 2 * F) / kSteps, glass + 5.0 * k);
    }
  }
  // A roller shutter lowered from the head in half the windows.
  if (rng.Chance(0.5)) {
    const double lowered = rng.Uniform(0.15, 0.85) * (H - 0.5 * F);
    const double z1 = h + H - 0.5 * F;
    FillRect(f, a + 0.5 * F, z1 - lowered, a + W - 0.5 * F, z1, 150.0);
    for (double z = z1 - 0.05; z > z1 - lowered; z -= 0.05) {
      ShadeRect(f, a + 0.5 * F, z - 0.012, a + W - 0.5 * F, z, 0.85);
    }
  }
  // The recess: the head's reveal and the left one in shadow.
  ShadeRect(f, a, h + H - 0.09, a + W, h + H, 0.62);
  ShadeRect(f, a, h, a + 0.05, h + H - 0.09, 0.7);
}

}  // namespace

void Facade(Field& f, std::uint64_t seed) {
  const int n = f.n;
  const Field mottle = NoiseField(n, Fbm(Stream(seed, 0), 6, 6, 4, 0.5, n));
  const GradientNoise grain(Stream(seed, 1), std::min(n / 2, 128), std::min(n / 2, 128));
  ForEachTexel(f, [&](int x, int y, double u, double v, double& value) {
    value = 171.0 + 5.0 * mottle.at(x, y) + 4.0 * grain(u, v);
  });
  Rng rng(Stream(seed, 2));
  constexpr int kBays = static_cast<int>(kFacadeTileM / kFacadeBayM + 0.5);
  constexpr int kStoreys = static_cast<int>(kFacadeTileM / kFacadeStoreyM + 0.5);
  for (int s = 0; s < kStoreys; ++s) {
    for (int b = 0; b < kBays; ++b) {
      const double a = b * kFacadeBayM + 0.5 * (kFacadeBayM - kFacadeWindowWidthM);
      Window(f, a, s * kFacadeStoreyM + kFacadeSillHeightM, rng);
    }
  }
}

}  // namespace trackbed::render
