// Seeded value noise that any point of an unbounded plane can be computed from
// alone: the values on a square lattice are each one SplitMix64 output of the
// stream's seed and the lattice coordinates (no draw depends on another, and the
// lattice is anchored at the world's origin, not at a grid's corner), blended
// with Perlin's (2002) quintic fade so the field has a continuous gradient.
// The terrain's heights and the soil's variation are such fields, so a tile of
// a world of any size needs nothing but the seed.
#pragma once

#include <cstdint>

namespace trackbed::sim {

/// One value-noise field in [−1, 1]. Cheap to copy; thread-safe (no state).
class LatticeNoise {
 public:
  /// `stream_seed`: the field's own seed (split_mix::Stream of the scene's seed);
  /// `spacing_m` > 0: the lattice spacing (the field's wavelength).
  LatticeNoise(std::uint64_t stream_seed, double spacing_m);

  /// The field at (x, y), in [−1, 1).
  double operator()(double x_m, double y_m) const;
  /// The value at lattice point (i, j), in [−1, 1): at (i, j) · spacing.
  double Lattice(std::int64_t i, std::int64_t j) const;

 private:
  std::uint64_t seed_;
  double spacing_m_;
};

}  // namespace trackbed::sim
