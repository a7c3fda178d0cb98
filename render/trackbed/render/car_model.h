#pragma once
// A parked car drawn from parts (objects of type `car`, docs/rendering.md "Parked
// cars"): its body around four wheel arches, a glasshouse with a roof and B-pillars,
// four wheels with tyres and rims, head and tail lamps and number plates. The parts
// are laid out for the car's length, width and height from the proportions of a
// European compact hatchback, the Volkswagen Golf VII (Volkswagen AG, technical data of
// the Golf 2013: length 4.255 m, width 1.799 m, height 1.452 m, wheelbase 2.637 m, front
// track 1.549 m, tyres 205/55 R16); the wheels keep that tyre's size and the plates the
// size of a German plate (DIN 74069: 520 × 110 mm). The renderer draws the parts; the
// rest of the simulation sees the car as its box.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace trackbed::render {

/// Tyre 205/55 R16 (ETRTO designation): 205 mm wide, sidewall 55 % of that, on a
/// 16-inch rim: 16 × 25.4 + 2 × 0.55 × 205 = 631.9 mm across.
inline constexpr double kCarTyreWidthM = 0.205;
inline constexpr double kCarRimDiameterM = 16 * 0.0254;
inline constexpr double kCarWheelDiameterM = kCarRimDiameterM + 2 * 0.55 * kCarTyreWidthM;
/// The reference car's measures [m] (Volkswagen Golf VII, as above).
inline constexpr double kCarReferenceLengthM = 4.255;
inline constexpr double kCarReferenceWidthM = 1.799;
inline constexpr double kCarReferenceWheelbaseM = 2.637;
inline constexpr double kCarReferenceTrackM = 1.549;
/// Number plate [m] (DIN 74069).
inline constexpr double kCarPlateWidthM = 0.52;
inline constexpr double kCarPlateHeightM = 0.11;

/// One part of a car, in the car's frame: x forward, y to the left, z up from the
/// ground under it [m].
struct CarPart {
  enum class Shape {
    kPrism,  ///< a box whose top may be shorter and narrower than its base
    kWheel,  ///< a cylinder across the car, its outer face on the side `side` says
  };
  Shape shape = Shape::kPrism;
  /// Texture name: empty for the painted parts (the car object's own appearance), else
  /// a plain grey of `albedo` under that name (procedural_texture.h's MakePlainTexture).
  std::string appearance;
  double albedo = 0.5;  ///< [0, 1], for a name without a texture of its own
  // A prism: its base spans x0..x1 and ±half_width at z0, its top top_x0..top_x1 and
  // ±top_half_width at z1 (a box when top and base agree).
  double x0 = 0, x1 = 0, top_x0 = 0, top_x1 = 0;
  double half_width = 0, top_half_width = 0, z0 = 0, z1 = 0;
  // A wheel: the centre of its outer face, its radius, its width inwards and the side
  // its outer face looks to (+1 left, −1 right).
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0, width = 0;
  int side = 1;

  /// The axis-aligned bounds of the part in the car's frame.
  Eigen::Vector3d Min() const;
  Eigen::Vector3d Max() const;
};

/// The parts of a car of `size_m` (length, width, height [m]), each inside the box of
/// that size standing on z = 0 and centred on x = y = 0; the wheels on the ground.
std::vector<CarPart> CarParts(const Eigen::Vector3d& size_m);

}  // namespace trackbed::render
