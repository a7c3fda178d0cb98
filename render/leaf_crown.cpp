// Leafy tree crowns: the sprays' pictures and the cards' layout (see leaf_crown.h).
#include "trackbed/render/leaf_crown.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "texture_blocks.h"

namespace trackbed::render {
namespace {

using texture_blocks::Rng;
using texture_blocks::Stream;

constexpr int kSamples = 4;  // per texel side: 16 samples of coverage per texel
constexpr int kTwigsPerSpray = 3;
constexpr double kTwigWidthM = 0.004;   // a current-year shoot (authored)
constexpr double kTwigGrey = 60.0;      // bark's darker tone (authored)
constexpr double kLeafSpacingM = 0.04;  // between leaves along a twig (authored)

// One leaf on the card [m]: base, unit axis towards the tip, length and width.
struct Leaf {
  Eigen::Vector2d base, axis;
  double length = 0.0, width = 0.0, tone = 0.0;
};

// Half the blade's width at s in [0, 1] from base to tip, over half its width: widest a
// third of the way up (a cordate-ovate outline), pointed at the tip.
double BladeProfile(double s) {
  if (s <= 0.0 || s >= 1.0) return 0.0;
  return std::sqrt(s) * (1.0 - s) / 0.38490017945975052;  // max of sqrt(s)(1-s) at s = 1/3
}

// The tone of the leaf at point p [m], or a negative value where p is not on it: lit
// tone on one half, 0.8 of it on the other (the blade folded along its midrib), 0.7 of
// it on the midrib (1 mm either side), as the `leaves` texture draws its leaves.
double LeafTone(const Leaf& leaf, const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - leaf.base;
  const double along = d.dot(leaf.axis);
  const double across = leaf.axis.x() * d.y() - leaf.axis.y() * d.x();
  const double s = along / leaf.length;
  if (std::abs(across) > 0.5 * leaf.width * BladeProfile(s)) return -1.0;
  const double fold = across > 0.0 ? 1.0 : 0.8;
  const double rib = std::abs(across) < 0.001 ? 0.7 : 1.0;
  return leaf.tone * fold * rib;
}

// Whether p lies on the twig from a to b.
bool OnTwig(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() <= 0.5 * kTwigWidthM;
}

// A spray's twigs (pairs of ends) and leaves, alternating along each twig, from `rng`.
void LaySpray(Rng& rng, std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>* twigs,
              std::vector<Leaf>* leaves) {
  const double side = kLeafCardSideM;
  for (int k = 0; k < kTwigsPerSpray; ++k) {
    const double y0 = side * (0.2 + 0.3 * k + rng.Uniform(-0.05, 0.05));
    const double y1 = y0 + side * rng.Uniform(-0.12, 0.12);
    const Eigen::Vector2d a(0.02 * side, y0), b(0.96 * side, y1);
    twigs->emplace_back(a, b);
    const Eigen::Vector2d dir = (b - a).normalized();
    const Eigen::Vector2d normal(-dir.y(), dir.x());
    int alternate = rng.Chance(0.5) ? 1 : -1;
    for (double s = rng.Uniform(0.02, 0.04); s < (b - a).norm(); s += kLeafSpacingM) {
      Leaf leaf;
      leaf.length = rng.Uniform(kLeafMinLengthM, kLeafMaxLengthM);
      leaf.width = kLeafWidthOverLength * leaf.length;
      // Turned 35-70 degrees off the twig towards its tip, on alternate sides; a petiole
      // of 2-4 cm between twig and blade (authored).
      const double turn = rng.Uniform(0.6, 1.2);  // tan of the angle off the twig
      leaf.axis = (dir + alternate * turn * normal).normalized();
      leaf.base = a + s * dir + rng.Uniform(0.02, 0.04) * leaf.axis;
      leaf.tone = rng.Uniform(70.0, 200.0);  // the `leaves` texture's range of lit tones
      leaves->push_back(leaf);
      alternate = -alternate;
    }
  }
}

LeafSpray DrawSpray(std::uint64_t seed, int n) {
  Rng rng(seed);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> twigs;
  std::vector<Leaf> leaves;
  LaySpray(rng, &twigs, &leaves);
  const double texel = kLeafCardSideM / n, sub = texel / kSamples;
  // Per sample, what it shows: the last leaf drawn over it, else a twig.
  std::vector<float> tone(static_cast<std::size_t>(n) * n * kSamples * kSamples, -1.0f);
  const int m = n * kSamples;
  for (const auto& [a, b] : twigs) {
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        const Eigen::Vector2d p((i + 0.5) * sub, (j + 0.5) * sub);
        if (OnTwig(a, b, p)) tone[static_cast<std::size_t>(j) * m + i] = kTwigGrey;
      }
    }
  }
  for (const Leaf& leaf : leaves) {
    const Eigen::Vector2d tip = leaf.base + leaf.length * leaf.axis;
    const double reach = 0.5 * leaf.width;
    const Eigen::Vector2d lo = leaf.base.cwiseMin(tip).array() - reach;
    const Eigen::Vector2d hi = leaf.base.cwiseMax(tip).array() + reach;
    const int i0 = std::max(0, static_cast<int>(std::floor(lo.x() / sub)));
    const int i1 = std::min(m - 1, static_cast<int>(std::ceil(hi.x() / sub)));
    const int j0 = std::max(0, static_cast<int>(std::floor(lo.y() / sub)));
    const int j1 = std::min(m - 1, static_cast<int>(std::ceil(hi.y() / sub)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const double t = LeafTone(leaf, Eigen::Vector2d((i + 0.5) * sub, (j + 0.5) * sub));
        if (t >= 0.0) tone[static_cast<std::size_t>(j) * m + i] = static_cast<float>(t);
      }
    }
  }
  LeafSpray out;
  out.size_px = n;
  out.grey.assign(static_cast<std::size_t>(n) * n, 0);
  out.coverage.assign(static_cast<std::size_t>(n) * n, 0);
  double covered_samples = 0.0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      double sum = 0.0;
      int count = 0;
      for (int sj = 0; sj < kSamples; ++sj) {
        for (int si = 0; si < kSamples; ++si) {
          const float t =
              tone[static_cast<std::size_t>(y * kSamples + sj) * m + (x * kSamples + si)];
          if (t < 0.0f) continue;
          sum += t;
          ++count;
        }
      }
      const std::size_t k = static_cast<std::size_t>(y) * n + x;
      out.coverage[k] = static_cast<std::uint8_t>((255 * count + 8) / 16);
      out.grey[k] = count > 0 ? static_cast<std::uint8_t>(std::lround(sum / count)) : 0;
      covered_samples += out.coverage[k] / 255.0;
    }
  }
  out.leaf_area_m2 = covered_samples * texel * texel;
  return out;
}

// A point uniform in the cube [-1, 1]^3, its coordinates drawn z, y, x: one draw a
// statement, so that no compiler's order of evaluating arguments changes the bytes.
Eigen::Vector3d UniformInCube(Rng& rng) {
  const double z = rng.Uniform(-1.0, 1.0);
  const double y = rng.Uniform(-1.0, 1.0);
  const double x = rng.Uniform(-1.0, 1.0);
  return Eigen::Vector3d(x, y, z);
}

// A uniformly distributed unit vector in 3D, by rejection from the cube (no trigonometry,
// whose last bits depend on the C library).
Eigen::Vector3d Direction3(Rng& rng) {
  for (;;) {
    const Eigen::Vector3d v = UniformInCube(rng);
    const double n2 = v.squaredNorm();
    if (n2 > 1e-4 && n2 <= 1.0) return v / std::sqrt(n2);
  }
}

std::uint64_t DoubleBits(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

}  // namespace

std::vector<LeafSpray> MakeLeafSprays(std::uint64_t seed, int size_px) {
  if (size_px < 16 || size_px > 1024 || (size_px & (size_px - 1)) != 0) {
    throw std::invalid_argument(
        "MakeLeafSprays: size_px must be a power of two in [16, 1024] (got " +
        std::to_string(size_px) + ")");
  }
  std::vector<LeafSpray> out;
  for (int k = 0; k < kLeafSprayVariants; ++k) {
    out.push_back(DrawSpray(Stream(seed, static_cast<std::uint64_t>(k)), size_px));
  }
  return out;
}

std::vector<LeafCard> LeafCrownCards(const Eigen::Vector3d& center, double radius_m,
                                     std::uint64_t tree_seed,
                                     const std::vector<double>& spray_leaf_area_m2) {
  const double half_diagonal = kLeafCardSideM / std::sqrt(2.0);
  if (!(radius_m > half_diagonal)) {
    throw std::invalid_argument("LeafCrownCards: the crown's radius " + std::to_string(radius_m) +
                                " m does not hold a card (half diagonal " +
                                std::to_string(half_diagonal) + " m)");
  }
  if (spray_leaf_area_m2.empty() ||
      std::any_of(spray_leaf_area_m2.begin(), spray_leaf_area_m2.end(),
                  [](double a) { return !(a > 0.0); })) {
    throw std::invalid_argument("LeafCrownCards: every spray must hold leaf area");
  }
  const double target = kCrownLeafAreaIndex * M_PI * radius_m * radius_m;
  const double reach = radius_m - half_diagonal;  // the cards' centres: corners inside
  Rng rng(tree_seed);
  std::vector<LeafCard> cards;
  double area = 0.0;
  while (area < target) {
    LeafCard c;
    Eigen::Vector3d p;
    do {
      p = UniformInCube(rng);
    } while (p.squaredNorm() > 1.0);
    c.center = center + reach * p;
    const Eigen::Vector3d n = Direction3(rng);
    Eigen::Vector3d u = Direction3(rng);
    while (std::abs(u.dot(n)) > 0.9) u = Direction3(rng);
    u = (u - u.dot(n) * n).normalized();
    c.half_u = 0.5 * kLeafCardSideM * u;
    c.half_v = 0.5 * kLeafCardSideM * n.cross(u);
    c.variant = static_cast<int>(rng.Next() % spray_leaf_area_m2.size());
    area += spray_leaf_area_m2[static_cast<std::size_t>(c.variant)];
    cards.push_back(c);
  }
  return cards;
}

std::uint64_t LeafCrownSeed(std::uint64_t scene_seed, const Eigen::Vector2d& tree_xy) {
  return Stream(scene_seed ^ texture_blocks::Mix(DoubleBits(tree_xy.x()) + texture_blocks::kGamma) ^
                    texture_blocks::Mix(DoubleBits(tree_xy.y())),
                0x1eafULL);
}

}  // namespace trackbed::render
