// The world's geodetic origin (see geodetic_origin.h).
#include "trackbed/sim/geodetic_origin.h"

#include <cmath>

#include "trackbed/common/option_error.h"
#include "trackbed/common/units.h"

namespace trackbed::sim {

void GeodeticOrigin::Validate() const {
  option_check::InRange("latitude_deg", latitude_deg, -90.0, 90.0);
  option_check::InRange("longitude_deg", longitude_deg, -180.0, 180.0);
  // The Mariana Trench's floor to Everest's summit, rounded outwards: where normal
  // gravity's second-order height reduction holds.
  option_check::InRange("elevation_m", elevation_m, -11000.0, 9000.0);
  option_check::InRange("heading_deg", heading_deg, -360.0, 360.0);
}

Eigen::Vector3d GeodeticOrigin::NorthInWorld() const {
  // x = cos h · E + sin h · N, y = −sin h · E + cos h · N: North is (sin h, cos h).
  const double h = units::Radians(heading_deg);
  return {std::sin(h), std::cos(h), 0.0};
}

Eigen::Vector3d GeodeticOrigin::EarthRateInWorld() const {
  const double phi = units::Radians(latitude_deg);
  return wgs84::kEarthRateRadps *
         (std::cos(phi) * NorthInWorld() + std::sin(phi) * Eigen::Vector3d::UnitZ());
}

double NormalGravityOnEllipsoid(double latitude_rad) {
  const double s2 = std::pow(std::sin(latitude_rad), 2);
  return wgs84::kGravityEquatorMps2 * (1.0 + wgs84::kSomiglianaK * s2) /
         std::sqrt(1.0 - wgs84::kEccentricitySquared * s2);
}

double GeodeticOrigin::NormalGravity() const {
  const double phi = units::Radians(latitude_deg);
  const double f = 1.0 / wgs84::kInverseFlattening;
  const double a = wgs84::kSemiMajorAxisM;
  const double h = elevation_m;
  const double s2 = std::pow(std::sin(phi), 2);
  return NormalGravityOnEllipsoid(phi) *
         (1.0 - 2.0 / a * (1.0 + f + wgs84::kGravityRatioM - 2.0 * f * s2) * h +
          3.0 * h * h / (a * a));
}

}  // namespace trackbed::sim
