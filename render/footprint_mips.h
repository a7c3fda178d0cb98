// A texture's mip chain pre-filtered for long pixel footprints (see surface_program.h).
// Private to the renderer.
//
// Layer 0 of each level is the isotropic chain: level i is level 0 box-filtered 2 × 2
// i times. Layer 1 + (m − 1)·directions + k, for anisotropy 2^m (m = 1 … kMaxAnisotropyLog2)
// and direction k (θ = k·π/directions), is that level also averaged along θ over 2^m of
// its texels: the mean of the texture over a footprint 2^m times longer than wide, in one
// trilinear lookup. Each doubling of the length averages two copies of the previous
// layer shifted ±half its length along θ (bilinear, wrapping around as the tile repeats).
// Only IEEE-exact arithmetic (+ − × ÷ sqrt) goes into the bytes: the same on every
// machine.
#pragma once

#include <cstdint>
#include <vector>

#include "trackbed/render/procedural_texture.h"

namespace trackbed::render {

/// Footprints up to 2^kMaxAnisotropyLog2 times longer than wide have their own layer.
constexpr int kMaxAnisotropyLog2 = 4;

struct FootprintMips {
  int directions = 0;  ///< directions of elongated footprints over [0, π); 0: layer 0 only
  int layers = 1;      ///< 1 + kMaxAnisotropyLog2 · directions
  /// levels[i]: level i (side size_px >> i) of every layer, layer after layer, rows of
  /// texels, down to 1 × 1.
  std::vector<std::vector<std::uint8_t>> levels;
};

/// The chain of `t` with `directions` directions (0, or a power of two ≥ 4).
FootprintMips MakeFootprintMips(const Texture& t, int directions);

}  // namespace trackbed::render
