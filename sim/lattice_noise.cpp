// Seeded lattice value noise (see lattice_noise.h).
#include "trackbed/sim/lattice_noise.h"

#include <cmath>

#include "trackbed/common/split_mix.h"

namespace trackbed::sim {
namespace {

// Quintic fade (Perlin 2002): C2-continuous interpolation weight on [0, 1]. Named apart
// from procedural_texture.cpp's Fade, which a unity build may compile beside it (that
// one must stay under that file's fp-contract=off).
double QuinticFade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

}  // namespace

LatticeNoise::LatticeNoise(std::uint64_t stream_seed, double spacing_m)
    : seed_(stream_seed), spacing_m_(spacing_m) {}

double LatticeNoise::Lattice(std::int64_t i, std::int64_t j) const {
  std::uint64_t h = split_mix::Mix(seed_ ^ static_cast<std::uint64_t>(i));
  h = split_mix::Mix(h ^ static_cast<std::uint64_t>(j));
  return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;  // [-1, 1)
}

double LatticeNoise::operator()(double x_m, double y_m) const {
  const double gx = x_m / spacing_m_, gy = y_m / spacing_m_;
  const double fx = std::floor(gx), fy = std::floor(gy);
  const auto i = static_cast<std::int64_t>(fx);
  const auto j = static_cast<std::int64_t>(fy);
  const double u = QuinticFade(gx - fx), v = QuinticFade(gy - fy);
  const double a = Lattice(i, j), b = Lattice(i + 1, j);
  const double c = Lattice(i, j + 1), d = Lattice(i + 1, j + 1);
  return (a + (b - a) * u) * (1.0 - v) + (c + (d - c) * u) * v;
}

}  // namespace trackbed::sim
