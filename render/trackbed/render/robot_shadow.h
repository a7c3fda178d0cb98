// The robot's own shadow (`scene.appearance.robot_shadow`): the sun's light on every
// surface is shadowed where a ray from the surface towards the sun passes through one
// of the robot's boxes (hull, tracks) at the robot's pose in that frame, so that the
// shadow moves with the robot as a real one does. The test is analytic, per fragment,
// in the surface program: for each box, the least growth δ of the box (along its own
// axes) at which the ray would hit it (slab method: δ* = max over the axes i, j of
// (A_i |d_j| − B_j |d_i|) / (|d_i| + |d_j|), A and B a slab's entry and exit distances
// times |d_i|, and ray entries behind the point excluded), so δ* ≤ 0 is in shadow. The
// edge is softened over the sun's disc: the light is smoothstep(−w, w, δ*) with w the
// sun's angular radius (0.2665°, the 0.533° mean apparent diameter) times the distance
// from the point to the box along the ray: a penumbra as wide as a real one
// (docs/camera_model.md, "The robot's own shadow").
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace trackbed::render {

/// A box of the robot that casts a shadow, axis-aligned in the robot's body frame.
struct ShadowBox {
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();  ///< centre in the body frame [m]
  Eigen::Vector3d size_m{1.0, 1.0, 1.0};               ///< extents along body x, y, z [m], > 0
};

/// Most boxes a robot's shadow takes.
inline constexpr int kMaxShadowBoxes = 6;
/// The sun's angular radius [rad]: half its mean apparent diameter, 0.533°.
inline constexpr double kSunAngularRadiusRad = 0.5 * 0.533 * 3.14159265358979323846 / 180.0;

/// What the surface program needs in a frame: per box (the first, the boxes' common
/// bounds, which lets a fragment far from the shadow skip the rest) the map from OpenGL
/// eye coordinates to the box's own (centred, its axes), its half extents and the
/// direction towards the sun in its axes.
struct ShadowFrame {
  int count = 0;                    ///< boxes, the bounds included
  std::vector<float> box_from_eye;  ///< count column-major 4 × 4 matrices
  std::vector<float> half_m;        ///< count × 3
  std::vector<float> sun_box;       ///< count × 3, unit
};

/// The frame's uniforms for `boxes` (1 to kMaxShadowBoxes) on a body at `T_world_body`,
/// `view` mapping world to eye coordinates, `sun` the unit vector towards the sun.
/// Throws std::invalid_argument for no box, too many or a size not > 0.
ShadowFrame MakeShadowFrame(const std::vector<ShadowBox>& boxes,
                            const Eigen::Isometry3d& T_world_body, const Eigen::Matrix4d& view,
                            const Eigen::Vector3d& sun);

/// The GLSL function `float RobotSunlit(vec3 eye)` (the share of the sun's disc a point
/// at eye coordinates `eye` sees past the boxes) and its uniforms.
const char* RobotShadowShaderSource();

/// The same, on the CPU in double (tests): the share of the sun's disc that world point
/// `p` sees past `boxes` on a body at `T_world_body`.
double RobotSunlit(const std::vector<ShadowBox>& boxes, const Eigen::Isometry3d& T_world_body,
                   const Eigen::Vector3d& sun, const Eigen::Vector3d& p);

}  // namespace trackbed::render
