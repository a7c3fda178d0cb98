// Ground truth for navigation in closed loop: how far the chassis is from the
// scene's obstacles, in the plane. The chassis footprint is its hull box seen from
// above (an oriented rectangle); obstacles are the colliding static objects
// (cylinders as circles, boxes as oriented rectangles).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "trackbed/sim/static_object.h"

namespace trackbed::runner {

/// Signed planar distance [m] between the footprint of a box of `size_xy_m` (length
/// along the body x, width along y) at `T_world_body` and the nearest colliding object:
/// the gap when apart, minus the smallest separating overlap when they overlap (so a
/// negative value is a collision); +infinity without colliding objects.
double ChassisClearance(const Eigen::Isometry3d& T_world_body, const Eigen::Vector2d& size_xy_m,
                        const std::vector<sim::StaticObject>& objects);

}  // namespace trackbed::runner
