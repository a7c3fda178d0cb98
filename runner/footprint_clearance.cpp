// Planar chassis–obstacle clearance (see footprint_clearance.h).
#include "trackbed/runner/footprint_clearance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace trackbed::runner {
namespace {

using Corners = std::array<Eigen::Vector2d, 4>;

Corners RectangleCorners(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& size) {
  const Eigen::Vector2d ax(std::cos(yaw), std::sin(yaw)), ay(-std::sin(yaw), std::cos(yaw));
  const Eigen::Vector2d hx = 0.5 * size.x() * ax, hy = 0.5 * size.y() * ay;
  return {centre + hx + hy, centre - hx + hy, centre - hx - hy, centre + hx - hy};
}

double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Separating-axis test over both rectangles' edge normals: the largest gap along any
// axis (negative: the smallest overlap when no axis separates them).
double LargestAxisGap(const Corners& a, const Corners& b) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Corners* poly : {&a, &b}) {
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d edge = (*poly)[k + 1] - (*poly)[k];
      const Eigen::Vector2d axis = Eigen::Vector2d(-edge.y(), edge.x()).normalized();
      double a_lo = 1e300, a_hi = -1e300, b_lo = 1e300, b_hi = -1e300;
      for (const Eigen::Vector2d& p : a) {
        a_lo = std::min(a_lo, p.dot(axis));
        a_hi = std::max(a_hi, p.dot(axis));
      }
      for (const Eigen::Vector2d& p : b) {
        b_lo = std::min(b_lo, p.dot(axis));
        b_hi = std::max(b_hi, p.dot(axis));
      }
      best = std::max(best, std::max(b_lo - a_hi, a_lo - b_hi));
    }
  }
  return best;
}

double RectangleRectangle(const Corners& a, const Corners& b) {
  const double gap = LargestAxisGap(a, b);
  if (gap <= 0.0) return gap;  // overlapping
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      d = std::min(d, PointSegmentDistance(a[i], b[j], b[(j + 1) % 4]));
      d = std::min(d, PointSegmentDistance(b[i], a[j], a[(j + 1) % 4]));
    }
  }
  return d;
}

double RectangleCircle(const Eigen::Vector2d& centre, double yaw, const Eigen::Vector2d& size,
                       const Eigen::Vector2d& c, double radius) {
  const Eigen::Vector2d ax(std::cos(yaw), std::sin(yaw)), ay(-std::sin(yaw), std::cos(yaw));
  const Eigen::Vector2d d = c - centre;
  const Eigen::Vector2d local(d.dot(ax), d.dot(ay));
  const Eigen::Vector2d half = 0.5 * size;
  const Eigen::Vector2d outside(std::max(std::abs(local.x()) - half.x(), 0.0),
                                std::max(std::abs(local.y()) - half.y(), 0.0));
  if (outside.x() > 0.0 || outside.y() > 0.0) return outside.norm() - radius;
  // Centre inside the rectangle: minus the distance to push it out, minus the radius.
  return -std::min(half.x() - std::abs(local.x()), half.y() - std::abs(local.y())) - radius;
}

}  // namespace

double ChassisClearance(const Eigen::Isometry3d& T_world_body, const Eigen::Vector2d& size_xy_m,
                        const std::vector<sim::StaticObject>& objects,
                        const std::vector<std::shared_ptr<const sim::PlacedMesh>>& meshes,
                        const Eigen::Vector2d& z_range_body_m) {
  const Eigen::Vector2d centre = T_world_body.translation().head<2>();
  const Eigen::Matrix3d& R = T_world_body.linear();
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const Corners chassis = RectangleCorners(centre, yaw, size_xy_m);
  double clearance = std::numeric_limits<double>::infinity();
  for (const sim::StaticObject& o : objects) {
    if (!o.collides) continue;
    const double d = o.shape == sim::StaticObject::Shape::kCylinder
                         ? RectangleCircle(centre, yaw, size_xy_m, o.center_m, o.radius_m)
                         : RectangleRectangle(chassis, RectangleCorners(o.center_m, o.yaw_rad,
                                                                        o.size_m.head<2>()));
    clearance = std::min(clearance, d);
  }
  if (!meshes.empty()) {
    const std::vector<Eigen::Vector2d> footprint(chassis.begin(), chassis.end());
    const double z = T_world_body.translation().z();
    for (const auto& m : meshes) {
      clearance = std::min(
          clearance, m->PlanDistance(footprint, z + z_range_body_m[0], z + z_range_body_m[1]));
    }
  }
  return clearance;
}

}  // namespace trackbed::runner
