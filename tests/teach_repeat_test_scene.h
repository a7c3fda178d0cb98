// A synthetic scene for the teach & repeat tests, without the simulator: a corridor whose
// two side walls and far wall carry randomly placed, rotated squares of random grey
// levels (planar textured patches, whose corners are Harris corners at known 3-D
// points), drawn by a pinhole camera on a robot that moves in the plane. Rendering is
// cv::fillConvexPoly with 1/16-pixel vertex precision and anti-aliased edges, painter's
// order; a frame takes a few milliseconds.
//
// World frame (docs/conventions.md): x forward along the corridor, y left, z up. The
// camera sits kCameraForward ahead of the body origin and kCameraHeight above the floor,
// level, looking along the body's x axis (OpenCV camera axes: x right, y down, z forward).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/common/pose2.h"
#include "trackbed/teach_repeat/teach_map.h"

namespace trackbed::teach_repeat::testing {

constexpr double kCameraForward = 0.2;  // [m] ahead of the body origin
constexpr double kCameraHeight = 0.4;   // [m] above the floor

/// The project's camera: 640×480, fx = fy = 381.4 px (docs/rendering.md, the robot's stereo rig).
inline geometry::PinholeCamera TestCamera() {
  geometry::PinholeCamera c;
  c.fx = 381.4;
  c.fy = 381.4;
  c.cx = 319.5;
  c.cy = 239.5;
  c.width_px = 640;
  c.height_px = 480;
  return c;
}

/// T_world_cam of the camera on a robot at planar pose `body`.
inline Eigen::Isometry3d CameraPose(const geometry::Pose2& body) {
  Eigen::Matrix3d R_body_cam;
  // Columns: the camera's x (right = −body y), y (down = −body z), z (forward = body x).
  R_body_cam << 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0, -1.0, 0.0;
  Eigen::Isometry3d T_body_cam = Eigen::Isometry3d::Identity();
  T_body_cam.linear() = R_body_cam;
  T_body_cam.translation() = Eigen::Vector3d(kCameraForward, 0.0, kCameraHeight);
  return geometry::ToIsometry(body) * T_body_cam;
}

struct CorridorOptions {
  double start_x_m = -2.0;    // walls begin here
  double far_wall_x_m = 7.0;  // the far wall
  double half_width_m = 1.2;  // side walls at y = ±half_width
  double height_m = 1.6;      // squares between z = 0 and height
  double density_per_m2 = 45.0;
  std::uint64_t seed = 1;
};

class CorridorScene {
 public:
  explicit CorridorScene(const CorridorOptions& options = {}) : o_(options) {
    std::mt19937_64 rng(o_.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double wall_length = o_.far_wall_x_m - o_.start_x_m;
    auto add = [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& along, double length) {
      const int n = static_cast<int>(o_.density_per_m2 * length * o_.height_m);
      const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d centre =
            origin + along * (length * unit(rng)) + up * (o_.height_m * unit(rng));
        const double side = 0.06 + 0.12 * unit(rng);
        const double angle = M_PI / 2.0 * unit(rng);
        Square s;
        for (int k = 0; k < 4; ++k) {
          const double a = angle + k * M_PI / 2.0 + M_PI / 4.0;
          const double r = side / std::sqrt(2.0);
          s.corners[static_cast<std::size_t>(k)] =
              centre + along * (r * std::cos(a)) + up * (r * std::sin(a));
        }
        s.centre = centre;
        // Grey levels away from the background's 128, light or dark.
        const double g = unit(rng);
        s.grey = static_cast<unsigned char>(g < 0.5 ? 15.0 + 200.0 * g : 40.0 + 200.0 * g);
        squares_.push_back(s);
      }
    };
    add({o_.start_x_m, o_.half_width_m, 0.0}, Eigen::Vector3d::UnitX(), wall_length);
    add({o_.start_x_m, -o_.half_width_m, 0.0}, Eigen::Vector3d::UnitX(), wall_length);
    add({o_.far_wall_x_m, -o_.half_width_m, 0.0}, Eigen::Vector3d::UnitY(), 2.0 * o_.half_width_m);
  }

  /// The image seen by a camera at T_world_cam (CV_8UC1 of the camera's size).
  cv::Mat Render(const Eigen::Isometry3d& T_world_cam,
                 const geometry::PinholeCamera& camera = TestCamera()) const {
    cv::Mat image(camera.height_px, camera.width_px, CV_8UC1, cv::Scalar(128));
    const Eigen::Isometry3d T_cam_world = T_world_cam.inverse();
    struct Visible {
      double depth;
      std::size_t index;
    };
    std::vector<Visible> order;
    for (std::size_t i = 0; i < squares_.size(); ++i) {
      const double z = (T_cam_world * squares_[i].centre).z();
      if (z > 0.1) order.push_back({z, i});
    }
    std::sort(order.begin(), order.end(), [](const Visible& a, const Visible& b) {
      return a.depth > b.depth || (a.depth == b.depth && a.index < b.index);
    });
    constexpr int kShift = 4;
    constexpr double kScale = 1 << kShift;
    for (const Visible& v : order) {
      const Square& s = squares_[v.index];
      std::array<cv::Point, 4> pts;
      bool ok = true;
      for (std::size_t k = 0; k < 4; ++k) {
        const Eigen::Vector3d p = T_cam_world * s.corners[k];
        if (p.z() < 0.05) {
          ok = false;
          break;
        }
        const double u = camera.fx * p.x() / p.z() + camera.cx;
        const double w = camera.fy * p.y() / p.z() + camera.cy;
        if (std::abs(u) > 1e5 || std::abs(w) > 1e5) {
          ok = false;
          break;
        }
        pts[k] = cv::Point(static_cast<int>(std::lround(u * kScale)),
                           static_cast<int>(std::lround(w * kScale)));
      }
      if (!ok) continue;
      cv::fillConvexPoly(image, pts.data(), 4, cv::Scalar(s.grey), cv::LINE_AA, kShift);
    }
    return image;
  }

  /// The scene point seen at pixel `px` by a camera at T_world_cam: the nearest wall hit
  /// within the walls' extent.
  std::optional<Eigen::Vector3d> RayCast(
      const Eigen::Isometry3d& T_world_cam, const cv::Point2f& px,
      const geometry::PinholeCamera& camera = TestCamera()) const {
    const Eigen::Vector3d o = T_world_cam.translation();
    const Eigen::Vector3d d =
        T_world_cam.linear() *
        Eigen::Vector3d((px.x - camera.cx) / camera.fx, (px.y - camera.cy) / camera.fy, 1.0);
    double best = 1e30;
    std::optional<Eigen::Vector3d> hit;
    auto consider = [&](double t) {
      if (!(t > 0.0) || t >= best) return;
      const Eigen::Vector3d p = o + t * d;
      // Squares may overhang the band of their centres by up to 0.13 m.
      constexpr double kOverhang = 0.2;
      if (p.z() < -kOverhang || p.z() > o_.height_m + kOverhang ||
          p.x() < o_.start_x_m - kOverhang || p.x() > o_.far_wall_x_m + 1e-9 ||
          std::abs(p.y()) > o_.half_width_m + 1e-9) {
        return;
      }
      best = t;
      hit = p;
    };
    if (d.y() != 0.0) {
      consider((o_.half_width_m - o.y()) / d.y());
      consider((-o_.half_width_m - o.y()) / d.y());
    }
    if (d.x() != 0.0) consider((o_.far_wall_x_m - o.x()) / d.x());
    return hit;
  }

  const CorridorOptions& options() const { return o_; }

 private:
  struct Square {
    std::array<Eigen::Vector3d, 4> corners;
    Eigen::Vector3d centre;
    unsigned char grey = 0;
  };
  CorridorOptions o_;
  std::vector<Square> squares_;
};

/// A uniform dark disc over the image: an occluder (a pedestrian) in front of the scene.
inline void DrawOccluder(cv::Mat* image, cv::Point2f centre, double radius_px) {
  cv::circle(*image,
             cv::Point(static_cast<int>(std::lround(centre.x * 16.0)),
                       static_cast<int>(std::lround(centre.y * 16.0))),
             static_cast<int>(std::lround(radius_px * 16.0)), cv::Scalar(35), cv::FILLED,
             cv::LINE_AA, 4);
}

}  // namespace trackbed::teach_repeat::testing
