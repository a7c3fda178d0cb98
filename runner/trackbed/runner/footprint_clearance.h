// Ground truth for navigation in closed loop: how far the chassis is from the
// scene's obstacles, in the plane. The chassis footprint is its hull box seen from
// above (an oriented rectangle); obstacles are the colliding static objects
// (cylinders as circles, boxes as oriented rectangles) and the colliding meshes'
// solids (each triangle within the chassis's height range, seen from above).
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/sim/static_object.h"
#include "trackbed/sim/triangle_mesh.h"

namespace trackbed::runner {

/// Signed planar distance [m] between the footprint of a box of `size_xy_m` (length
/// along the body x, width along y) at `T_world_body` and the nearest colliding object:
/// the gap when apart, minus the smallest separating overlap when they overlap (so a
/// negative value is a collision); +infinity without colliding objects. A mesh's
/// triangles count where their height range meets the chassis's, `z_range_body_m`
/// (lowest, highest) relative to the body's origin [m].
double ChassisClearance(const Eigen::Isometry3d& T_world_body, const Eigen::Vector2d& size_xy_m,
                        const std::vector<sim::StaticObject>& objects,
                        const std::vector<std::shared_ptr<const sim::PlacedMesh>>& meshes = {},
                        const Eigen::Vector2d& z_range_body_m =
                            Eigen::Vector2d(-std::numeric_limits<double>::infinity(),
                                            std::numeric_limits<double>::infinity()));

}  // namespace trackbed::runner
