// The constant-velocity motion model that visual odometry vets its consensuses
// against and that the localization stack coasts VO's pose with over failed frames.
#pragma once

#include <Eigen/Geometry>

namespace trackbed::estimation {

/// The rigid motion T, made over an interval dt_from, continued at constant velocity
/// over dt_to: its rotation angle (about the same axis) and its translation scaled by
/// dt_to / dt_from (by 1 when dt_from <= 0).
Eigen::Isometry3d ContinuedMotion(const Eigen::Isometry3d& T, double dt_from, double dt_to);

}  // namespace trackbed::estimation
