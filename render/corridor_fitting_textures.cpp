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

void Luminaire(Field& f, std::uint64_t seed) { SmoothSurface(f, seed, 0.99, 0.5); }

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
  // (-10 %) and its right half lit (+4 %); the tile's edge falls on plain panel between
  // two channels, so the tile repeats without a seam.
  constexpr int kChannels = 20;
  ForEachTexel(f, [&](int, int, double u, double, double& value) {
    const double p = u * kChannels + 0.5;
    const double w = p - std::floor(p);  // position in the pitch
    if (w < 0.15) {
      value *= 0.90;
    } else if (w < 0.30) {
      value *= 1.04;
    }
  });
}

void NoticeBoard(Field& f, std::uint64_t seed) {
  // Cork: a fine granular mottle. The tile is the board's width (0.9 m); the board
  // fills its lower 2/3, the rest (never seen) is frame, so the frame meets itself
  // across every edge of the tile.
  f = NoiseField(f.n, Fbm(Stream(seed, 0), 64, 64, 2, 0.5, f.n));
  SetMeanStd(f, 255.0 * 0.35, 6.0);
  constexpr double kTile = kBoardTileM;
  constexpr double kW = 0.9 / kTile, kH = 0.6 / kTile, kFrame = 0.02 / kTile;  // tile units
  Rng rng(Stream(seed, 1));
  const int sheets = 3 + static_cast<int>(rng.Uniform(0.0, 3.0));
  for (int k = 0; k < sheets; ++k) {
    const bool portrait = rng.Uniform(0.0, 1.0) < 0.7;
    const double w = (portrait ? 0.21 : 0.297) / kTile, h = (portrait ? 0.297 : 0.21) / kTile;
    const double margin = kFrame + 0.01 / kTile;
    const double u0 = rng.Uniform(margin, kW - margin - w);
    const double v0 = rng.Uniform(margin, kH - margin - h);
    FittingRect(f, u0, v0, u0 + w, v0 + h, 255.0 * 0.85);
    // Lines of text 3 mm high every 6 mm within 20 mm margins, each ending where it ends.
    const double line = 0.003 / kTile, pitch = 0.006 / kTile, side = 0.02 / kTile;
    for (double v = v0 + h - 1.5 * side; v > v0 + 1.5 * side; v -= pitch) {
      const double end = u0 + side + rng.Uniform(0.5, 1.0) * (w - 2 * side);
      FittingRect(f, u0 + side, v - line, end, v, 255.0 * 0.3);
    }
  }
  // The aluminium frame: the board's rim, and the tile beyond the board (antialiased on
  // the cork's side).
  const double frame = 255.0 * 0.6;
  ForEachTexel(f, [&](int, int, double u, double v, double& value) {
    const double inside =
        std::min(std::min(u - kFrame, kW - kFrame - u), std::min(v - kFrame, kH - kFrame - v));
    const double c = Coverage(inside * f.n);
    value += c * (frame - value);
  });
}

void Extinguisher(Field& f, std::uint64_t seed) {
  SmoothSurface(f, seed, 0.1, 0.8);
  FittingRect(f, 0.1, 0.20, 0.35, 0.35, 255.0 * 0.8);
}

}  // namespace trackbed::render
