// Obstacles as circles in the plane: what every navigation method here sees.
//
// A circle is the obstacle's own physical extent (radius 0 is the point
// obstacle of Jung & Kim 2014). Safety margins (the paper's d_max) are added
// by the methods that use them, never baked into the circle. Walls enter as
// chains of circles no farther apart than d_max (Jung & Kim 2014's safety radius).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace trackbed::navigation {

/// A circular obstacle in the world frame: centre [m] and physical radius [m] (>= 0).
struct Circle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
};

/// Signed distance [m] from `p_world` to the circle's surface (negative inside).
double SurfaceDistance(const Eigen::Vector2d& p_world, const Circle& obstacle);

/// Clearance [m] of a disk of radius `footprint_radius_m` centred at `p_world`: the
/// distance from the disk's edge to the nearest obstacle surface, negative when they
/// overlap; +infinity without obstacles.
double FootprintClearance(const Eigen::Vector2d& p_world, double footprint_radius_m,
                          const std::vector<Circle>& obstacles);

/// True when `p_world` lies strictly inside some obstacle's physical circle.
bool InsideAnyObstacle(const Eigen::Vector2d& p_world, const std::vector<Circle>& obstacles);

/// A straight wall from `a` to `b` as a chain of circles of radius `radius_m`, the
/// first centred at `a`, the last at `b`, consecutive centres evenly spaced and at
/// most `max_spacing_m` apart (> 0; choose <= d_max so the avoider never sees a gap
/// the safety circles would miss). A zero-length wall is one circle. Throws
/// std::invalid_argument for a non-positive spacing or a negative radius.
std::vector<Circle> WallCircles(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius_m,
                                double max_spacing_m);

}  // namespace trackbed::navigation
