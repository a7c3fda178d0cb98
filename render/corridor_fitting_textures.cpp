// The textures of the corridor fittings (see corridor_fitting_textures.h). Layout in tile
// units as every recipe; randomness from the integer hash and SplitMix64 only, floating
// point + − × ÷ sqrt floor, so the bytes are the same on every machine.
#include "corridor_fitting_textures.h"

#include <algorithm>
#include <cmath>

// Fusing a·b + c into one FMA changes rounding (see procedural_texture.cpp).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "texture_blocks.h"

namespace trackbed::render {
namespace {

using namespace texture_blocks;  // NOLINT: the recipes are written in its terms

// Sets the rectangle [u0, u1] × [v0, v1] (tile units) to `tone`, antialiased.
void FittingRect(Field& f, double u0, double v0, double u1, double v1, double tone) {
  const int n = f.n;
  const double hx = 0.5 * (u1 - u0) * n, hy = 0.5 * (v1 - v0) * n;
  ForEachInBox(f, 0.5 * (u0 + u1) * n, 0.5 * (v0 + v1) * n, hx + 1.0, hy + 1.0,
               [&](double& value, double dx, double dy, int, int) {
                 const double c = Coverage(std::abs(dx) - hx) * Coverage(std::abs(dy) - hy);
                 value += c * (tone - value);
               });
}

// A smooth painted or moulded surface of reflectance `r` with a faint mottle.
void SmoothSurface(Field& f, std::uint64_t seed, double r, double sd) {
  f = NoiseField(f.n, Fbm(Stream(seed, 0), 4, 4, 3, 0.5, f.n));
  SetMeanStd(f, 255.0 * r, sd);
}

}  // namespace

void Skirting(Field& f, std::uint64_t seed) { SmoothSurface(f, seed, 0.15, 1.0); }

void DoorFrame(Field& f, std::uint64_t seed) { SmoothSurface(f, seed, 0.5, 1.0); }

void Luminaire(Field& f, std::uint64_t) {
  for (double& v : f.v) v = 255.0;
}

void SwitchPlate(Field& f, std::uint64_t seed) {
  SmoothSurface(f, seed, 0.85, 0.5);
  // The rocker, 55 mm of the 80 mm plate, centred, outlined by a 1 mm gap in shadow.
  const double r0 = 0.5 - 0.5 * 0.055 / 0.08, r1 = 0.5 + 0.5 * 0.055 / 0.08;
  const double gap = 0.001 / 0.08;
  FittingRect(f, r0 - gap, r0 - gap, r1 + gap, r1 + gap, 255.0 * 0.4);
  FittingRect(f, r0, r0, r1, r1, 255.0 * 0.87);
}

void Radiator(Field& f, std::uint64_t seed) {
  SmoothSurface(f, seed, 0.85, 0.8);
  // A channel every 50 mm (20 per metre tile): 15 mm wide, its left half in shade
  // (-10 %) and its right half lit (+4 %).
  constexpr int kChannels = 20;
  ForEachTexel(f, [&](int, int, double u, double, double& value) {
    const double w = u * kChannels - std::floor(u * kChannels);  // position in the pitch
    if (w < 0.15) value *= 0.90;
    else if (w < 0.30) value *= 1.04;
  });
}

void NoticeBoard(Field& f, std::uint64_t seed) {
  // Cork: a fine granular mottle.
  f = NoiseField(f.n, Fbm(Stream(seed, 0), 64, 64, 2, 0.5, f.n));
  SetMeanStd(f, 255.0 * 0.35, 6.0);
  constexpr double kW = 0.9, kH = 0.6, kFrame = 0.02;  // [m] = tile units (1 m tile)
  Rng rng(Stream(seed, 1));
  const int sheets = 3 + static_cast<int>(rng.Uniform(0.0, 3.0));
  for (int k = 0; k < sheets; ++k) {
    const bool portrait = rng.Uniform(0.0, 1.0) < 0.7;
    const double w = portrait ? 0.21 : 0.297, h = portrait ? 0.297 : 0.21;
    const double u0 = rng.Uniform(kFrame + 0.01, kW - kFrame - 0.01 - w);
    const double v0 = rng.Uniform(kFrame + 0.01, kH - kFrame - 0.01 - h);
    FittingRect(f, u0, v0, u0 + w, v0 + h, 255.0 * 0.85);
    // Lines of text 3 mm high every 6 mm, 20 mm margins; each line's end drawn.
    for (double v = v0 + h - 0.03; v > v0 + 0.03; v -= 0.006) {
      const double end = u0 + 0.02 + rng.Uniform(0.5, 1.0) * (w - 0.04);
      FittingRect(f, u0 + 0.02, v - 0.003, end, v, 255.0 * 0.3);
    }
  }
  // The aluminium frame around the board.
  FittingRect(f, 0.0, 0.0, kW, kFrame, 255.0 * 0.6);
  FittingRect(f, 0.0, kH - kFrame, kW, kH, 255.0 * 0.6);
  FittingRect(f, 0.0, 0.0, kFrame, kH, 255.0 * 0.6);
  FittingRect(f, kW - kFrame, 0.0, kW, kH, 255.0 * 0.6);
}

void Extinguisher(Field& f, std::uint64_t seed) {
  SmoothSurface(f, seed, 0.1, 0.8);
  FittingRect(f, 0.0, 0.20, 0.25, 0.35, 255.0 * 0.8);
}

}  // namespace trackbed::render
