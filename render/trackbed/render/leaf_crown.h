// Leafy tree crowns (`scene.appearance.crowns: leaves`, docs/rendering.md, "Leafy
// crowns"): a crown is a cloud of leaf cards, each a flat square picture of a spray of
// leaves on a twig (grey and coverage), placed and turned from the tree's seed inside
// the crown's sphere until the cards' leaf area is the cited leaf area index over the
// crown's projection. Pure functions: the same seed gives the same bytes.
//
// Sources (docs/rendering.md has the table):
// - leaf blades 6-10 cm long and about as broad, cordate: Tilia x europaea, the common
//   lime of central European streets (Stace, New Flora of the British Isles, 3rd ed.
//   2010);
// - leaf area index 4.5 over the crown's projection: the global mean (+-2.5) of field
//   measurements after outlier removal (Asner, Scurlock & Hicke 2003, Global Ecology and
//   Biogeography 12: 191-205);
// - leaf area spread evenly through the crown's volume (the crown as a turbid medium of
//   uniform leaf area density, Norman & Welles 1983) and the cards' normals uniform over
//   the sphere (the spherical leaf angle distribution, de Wit 1965).
// The spray's layout (a twig across the card, leaves alternate along it) and the card's
// size are authored.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace trackbed::render {

/// Leaf area index over the crown's projection (Asner, Scurlock & Hicke 2003).
inline constexpr double kCrownLeafAreaIndex = 4.5;
/// Leaf blade length range [m] (Tilia x europaea, Stace 2010); the width is 0.9 of it.
inline constexpr double kLeafMinLengthM = 0.06;
inline constexpr double kLeafMaxLengthM = 0.10;
inline constexpr double kLeafWidthOverLength = 0.9;
/// Side of a leaf card [m] (authored: a spray of a shoot's leaves).
inline constexpr double kLeafCardSideM = 0.5;
/// Pictures of sprays the cards choose from.
inline constexpr int kLeafSprayVariants = 4;

/// The picture of one spray of leaves on a card, `size_px` square, rows from the card's
/// v = 0 edge: grey (255 x reflectance, the leaves' lit tone) and coverage (255 = the
/// texel wholly leaf or twig, 0 = none).
struct LeafSpray {
  int size_px = 0;
  std::vector<std::uint8_t> grey;
  std::vector<std::uint8_t> coverage;
  double leaf_area_m2 = 0.0;  ///< the card's area its coverage covers (one side)
};

/// The kLeafSprayVariants pictures drawn from `seed`. Throws std::invalid_argument when
/// `size_px` is not a power of two in [16, 1024].
std::vector<LeafSpray> MakeLeafSprays(std::uint64_t seed, int size_px = 256);

/// One card: a square about `center` spanned by `half_u` and `half_v` (orthogonal, each
/// half a side long), showing spray `variant`.
struct LeafCard {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d half_v = Eigen::Vector3d::UnitY();
  int variant = 0;
  Eigen::Vector3d Normal() const { return half_u.cross(half_v).normalized(); }
};

/// The cards of a crown of `radius_m` about `center` (world frame), drawn from
/// `tree_seed`: each wholly inside the sphere, their leaf area (the sprays'
/// `leaf_area_m2`, one per variant) summing to kCrownLeafAreaIndex x pi radius^2 within
/// one card's. Throws std::invalid_argument when the radius is not above the card's
/// half diagonal or a spray holds no leaf area.
std::vector<LeafCard> LeafCrownCards(const Eigen::Vector3d& center, double radius_m,
                                     std::uint64_t tree_seed,
                                     const std::vector<double>& spray_leaf_area_m2);

/// A tree's seed from the scene's and its position (so that other objects do not change
/// its crown).
std::uint64_t LeafCrownSeed(std::uint64_t scene_seed, const Eigen::Vector2d& tree_xy);

}  // namespace trackbed::render
