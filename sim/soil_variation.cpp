// Seeded soil variation fields (see soil_variation.h).
#include "trackbed/sim/soil_variation.h"

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/sim/lattice_noise.h"

namespace trackbed::sim {

void SoilVariationOptions::Validate() const {
  option_check::InRange("amplitude", amplitude, 0.0, 0.9);
  option_check::Positive("correlation_length_m", correlation_length_m);
}

SoilVariation::SoilVariation(const SoilVariationOptions& options, std::uint64_t seed)
    : options_(options), seed_(seed) {
  options_.Validate();
}

double SoilVariation::Value(Field f, double x_m, double y_m) const {
  // One independent field per parameter: its own stream of the seed.
  return LatticeNoise(split_mix::Stream(seed_, static_cast<std::uint64_t>(f)),
                      options_.correlation_length_m)(x_m, y_m);
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
