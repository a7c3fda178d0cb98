// Where on the Earth the world's origin lies (`scene.geodetic_origin`): its WGS 84
// latitude, longitude and height, and how the world's axes turn against East–North–Up.
// What it changes is physical: the Earth's rotation, which a gyro at rest senses
// (EarthRateInWorld), and the normal gravity at the origin (NormalGravity), which the
// scenario takes for scene.world.gravity_mps2 where that key is not given
// (docs/scenario_format.md). The world stays local metres: nothing is projected.
//
// The axes follow SDF's <spherical_coordinates> (sdformat 1.9's description, and
// ignition-math 6's SphericalCoordinates::LOCAL2): the world's x is East turned by
// `heading_deg` about Up, counter-clockwise seen from above (0: x East, y North, z Up;
// 90: x North, y West).
#pragma once

#include <Eigen/Core>

namespace trackbed::sim {

/// WGS 84's constants (NIMA TR8350.2, 3rd ed., 2000, tables 3.1 and 3.4).
namespace wgs84 {
/// The Earth's angular velocity [rad/s].
constexpr double kEarthRateRadps = 7.292115e-5;
/// Semi-major axis [m].
constexpr double kSemiMajorAxisM = 6378137.0;
/// Flattening 1/f.
constexpr double kInverseFlattening = 298.257223563;
/// First eccentricity squared.
constexpr double kEccentricitySquared = 6.69437999014e-3;
/// Normal gravity at the equator and at the poles [m/s²].
constexpr double kGravityEquatorMps2 = 9.7803253359;
constexpr double kGravityPoleMps2 = 9.8321849378;
/// Somigliana's constant k = (b·γp)/(a·γe) − 1.
constexpr double kSomiglianaK = 1.93185265241e-3;
/// m = ω²a²b/GM.
constexpr double kGravityRatioM = 3.44978650684e-3;
}  // namespace wgs84

struct GeodeticOrigin {
  /// Geodetic latitude of the world's origin [deg], in [−90, 90] (north positive).
  double latitude_deg = 0.0;
  /// Longitude [deg], in [−180, 180] (east positive). Recorded; nothing depends on it.
  double longitude_deg = 0.0;
  /// Height above the WGS 84 ellipsoid [m], in [−11000, 9000].
  double elevation_m = 0.0;
  /// The world's +x from East, counter-clockwise about Up [deg], in [−360, 360]
  /// (SDF's <heading_deg>).
  double heading_deg = 0.0;

  /// Throws OptionError naming the field out of range or not finite.
  void Validate() const;

  /// North in the world's axes (a unit vector in the horizontal plane).
  Eigen::Vector3d NorthInWorld() const;

  /// The Earth's rotation relative to an inertial frame, in the world's axes [rad/s]:
  /// ω (cos φ · North + sin φ · Up).
  Eigen::Vector3d EarthRateInWorld() const;

  /// WGS 84's normal gravity at the origin [m/s²]: Somigliana's closed form at the
  /// latitude, reduced to the height by TR8350.2's eq. 4-3 (second order in h).
  double NormalGravity() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("latitude_deg", &latitude_deg);
    a->Visit("longitude_deg", &longitude_deg);
    a->Visit("elevation_m", &elevation_m);
    a->Visit("heading_deg", &heading_deg);
  }
};

/// Somigliana's normal gravity on the WGS 84 ellipsoid at geodetic latitude
/// `latitude_rad` [m/s²].
double NormalGravityOnEllipsoid(double latitude_rad);

}  // namespace trackbed::sim
