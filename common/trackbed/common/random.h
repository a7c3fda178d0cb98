// The one seeded random generator of trackbed, with draws whose output is fixed by
// this file rather than by a standard library: std::uniform_int_distribution and
// std::normal_distribution are left to each library by the C++ standard, so they
// give other numbers under libc++ or MSVC than under GNU libstdc++. The engine is
// std::mt19937_64, whose output sequence the standard does fix.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace trackbed::random {

/// 53 random bits to a double in [0, 1): exact, the same on every platform.
constexpr double UnitInterval(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// 53 random bits to a double in (0, 1) (the centre of each of 2^53 bins), safe for log.
constexpr double OpenUnitInterval(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

/// A standard normal draw from two uniforms u1 in (0, 1] and u2 in [0, 1): the
/// Box–Muller transform (Box & Muller 1958), cosine branch.
inline double BoxMuller(double u1, double u2) {
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

/// A seeded generator. Not thread-safe; give each component its own.
class Generator {
 public:
  explicit Generator(std::uint64_t seed) : engine_(seed) {}

  /// 64 random bits.
  std::uint64_t Bits() { return engine_(); }
  /// Uniform in [0, 1).
  double Uniform() { return UnitInterval(engine_()); }
  /// Uniform in [lo, hi): lo + (hi − lo)·Uniform().
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Uniform integer in [0, n), n ≥ 1, without modulo bias: draws above the largest
  /// multiple of n are rejected and redrawn, the rest taken modulo n.
  std::uint64_t UniformIndex(std::uint64_t n);
  /// Standard normal (mean 0, standard deviation 1): Box–Muller from two draws.
  double Gaussian() {
    const double u1 = OpenUnitInterval(engine_());
    return BoxMuller(u1, UnitInterval(engine_()));
  }

  /// Same state: the same draws follow.
  friend bool operator==(const Generator& a, const Generator& b) { return a.engine_ == b.engine_; }
  friend bool operator!=(const Generator& a, const Generator& b) { return !(a == b); }

 private:
  std::mt19937_64 engine_;
};

inline std::uint64_t Generator::UniformIndex(std::uint64_t n) {
  // Accept only draws below the largest multiple of n, so every residue is equally likely.
  const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % n + 1) % n;
  std::uint64_t x = engine_();
  while (x > limit) x = engine_();
  return x % n;
}

}  // namespace trackbed::random
