// Circle obstacles and walls as chains of circles (see circle_obstacle.h).
#include "trackbed/navigation/circle_obstacle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace trackbed::navigation {

double SurfaceDistance(const Eigen::Vector2d& p_world, const Circle& obstacle) {
  return (p_world - obstacle.centre).norm() - obstacle.radius_m;
}

double FootprintClearance(const Eigen::Vector2d& p_world, double footprint_radius_m,
                          const std::vector<Circle>& obstacles) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const Circle& c : obstacles) {
    clearance = std::min(clearance, SurfaceDistance(p_world, c) - footprint_radius_m);
  }
  return clearance;
}

bool InsideAnyObstacle(const Eigen::Vector2d& p_world, const std::vector<Circle>& obstacles) {
  return std::any_of(obstacles.begin(), obstacles.end(),
                     [&](const Circle& c) { return SurfaceDistance(p_world, c) < 0.0; });
}

std::vector<Circle> WallCircles(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius_m,
                                double max_spacing_m) {
  if (!(max_spacing_m > 0.0) || !std::isfinite(max_spacing_m)) {
    throw std::invalid_argument("WallCircles: max_spacing_m must be > 0");
  }
  if (!(radius_m >= 0.0) || !std::isfinite(radius_m)) {
    throw std::invalid_argument("WallCircles: radius_m must be >= 0");
  }
  const double length = (b - a).norm();
  const int segments = std::max(1, static_cast<int>(std::ceil(length / max_spacing_m - 1e-12)));
  std::vector<Circle> chain;
  if (length == 0.0) return {Circle{a, radius_m}};
  chain.reserve(segments + 1);
  for (int k = 0; k <= segments; ++k) {
    const double s = static_cast<double>(k) / segments;
    chain.push_back(Circle{a + s * (b - a), radius_m});
  }
  return chain;
}

}  // namespace trackbed::navigation
