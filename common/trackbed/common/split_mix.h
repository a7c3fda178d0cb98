// SplitMix64 (Steele, Lea & Flood 2014), the counter-based mixer every seeded
// stream in trackbed is derived with: one 64-bit value per index, so any
// frame's, scan's or texel's randomness needs no earlier draw.
#pragma once

#include <cstdint>

namespace trackbed::split_mix {

/// SplitMix64's increment (the golden ratio in 64 bits).
constexpr std::uint64_t kGamma = 0x9e3779b97f4a7c15ULL;

/// SplitMix64's output function: a bijective 64-bit mixer.
constexpr std::uint64_t Finalize(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// One SplitMix64 step from state z: the increment, then the output function.
constexpr std::uint64_t Mix(std::uint64_t z) { return Finalize(z + kGamma); }

/// The seed of independent stream k of `seed` (the (k + 1)-th SplitMix64 output).
constexpr std::uint64_t Stream(std::uint64_t seed, std::uint64_t k) {
  return Finalize(seed + (k + 1) * kGamma);
}

}  // namespace trackbed::split_mix
