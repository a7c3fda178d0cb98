// Unit conversions, written once so that every library converts the same way (and
// with the same floating-point operations).
#pragma once

#include <cmath>

namespace trackbed::units {

/// Degrees to radians: deg · π / 180.
constexpr double Radians(double deg) { return deg * M_PI / 180.0; }

/// Radians to degrees: rad · 180 / π.
constexpr double Degrees(double rad) { return rad * 180.0 / M_PI; }

/// Standard gravity [m/s²] (CGPM 1901), the g of a data sheet's per-g and µg figures.
inline constexpr double kStandardGravity = 9.80665;

}  // namespace trackbed::units
