// Seeded soil variation fields (see soil_variation.h).
#include "trackbed/sim/soil_variation.h"

#include <cmath>

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"

namespace trackbed::sim {
namespace {

// Quintic fade (Perlin 2002): C2-continuous interpolation weight on [0, 1].
double Fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

}  // namespace

void SoilVariationOptions::Validate() const {
  option_check::InRange("amplitude", amplitude, 0.0, 0.9);
  option_check::Positive("correlation_length_m", correlation_length_m);
}

SoilVariation::SoilVariation(const SoilVariationOptions& options, std::uint64_t seed)
    : options_(options), seed_(seed) {
  options_.Validate();
}

double SoilVariation::Lattice(Field f, std::int64_t i, std::int64_t j) const {
  // One SplitMix64 output per (field, i, j): no draw depends on another.
  std::uint64_t h = split_mix::Stream(seed_, static_cast<std::uint64_t>(f));
  h = split_mix::Mix(h ^ static_cast<std::uint64_t>(i));
  h = split_mix::Mix(h ^ static_cast<std::uint64_t>(j));
  return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;  // [-1, 1)
}

double SoilVariation::Value(Field f, double x_m, double y_m) const {
  const double gx = x_m / options_.correlation_length_m;
  const double gy = y_m / options_.correlation_length_m;
  const double fx = std::floor(gx), fy = std::floor(gy);
  const auto i = static_cast<std::int64_t>(fx);
  const auto j = static_cast<std::int64_t>(fy);
  const double u = Fade(gx - fx), v = Fade(gy - fy);
  const double a = Lattice(f, i, j), b = Lattice(f, i + 1, j);
  const double c = Lattice(f, i, j + 1), d = Lattice(f, i + 1, j + 1);
  return (a + (b - a) * u) * (1.0 - v) + (c + (d - c) * u) * v;
}

SoilPoint SoilVariation::Apply(const SoilPoint& base, double x_m, double y_m) const {
  if (off() || base.IsRigid()) return base;  // floors and paving do not vary
  const double amp = options_.amplitude;
  auto scale = [&](Field f) { return 1.0 + amp * Value(f, x_m, y_m); };
  SoilPoint s = base;
  s.cohesion_pa *= scale(kCohesion);
  s.SetTanPhi(base.tan_phi * scale(kTanPhi));
  const double k_scale = scale(kShearModulus);  // grousers' anisotropy is kept
  s.shear_modulus_m *= k_scale;
  s.lateral_shear_modulus_m *= k_scale;
  s.bekker_kc *= scale(kKc);
  s.bekker_kphi *= scale(kKphi);
  return s;
}

}  // namespace trackbed::sim
