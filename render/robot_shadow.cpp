// The robot's own shadow (see robot_shadow.h).
#include "trackbed/render/robot_shadow.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace trackbed::render {
namespace {

// The least growth of a box of half extents `half` (centred at the origin, its axes)
// at which the ray p + t d, t >= 0, meets it (<= 0: it does), as the shader computes it.
double Growth(const Eigen::Vector3d& half, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  Eigen::Vector3d ad, a, b;
  for (int i = 0; i < 3; ++i) {
    const double s = d[i] < 0.0 ? -1.0 : 1.0;
    ad[i] = std::max(std::abs(d[i]), 1e-6);
    a[i] = -half[i] - p[i] * s;  // entry distance times |d_i|
    b[i] = half[i] - p[i] * s;   // exit
  }
  double g = std::max({-b.x(), -b.y(), -b.z()});  // exits behind the point
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) g = std::max(g, (a[i] * ad[j] - b[j] * ad[i]) / (ad[i] + ad[j]));
  }
  return g;
}

// GLSL's smoothstep, as the shader's RobotSunlit computes it.
double GlslSmoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// The boxes' common bounds first, then the boxes.
std::vector<ShadowBox> WithBounds(const std::vector<ShadowBox>& boxes) {
  if (boxes.empty() || static_cast<int>(boxes.size()) > kMaxShadowBoxes) {
    throw std::invalid_argument("robot shadow: 1 to " + std::to_string(kMaxShadowBoxes) +
                                " boxes (got " + std::to_string(boxes.size()) + ")");
  }
  Eigen::AlignedBox3d bounds;
  for (const ShadowBox& b : boxes) {
    if (!(b.size_m.minCoeff() > 0.0)) {
      throw std::invalid_argument("robot shadow: a box's size must be > 0");
    }
    bounds.extend(b.center_m - 0.5 * b.size_m);
    bounds.extend(b.center_m + 0.5 * b.size_m);
  }
  std::vector<ShadowBox> out{{bounds.center(), bounds.sizes()}};
  out.insert(out.end(), boxes.begin(), boxes.end());
  return out;
}

}  // namespace

ShadowFrame MakeShadowFrame(const std::vector<ShadowBox>& boxes,
                            const Eigen::Isometry3d& T_world_body, const Eigen::Matrix4d& view,
                            const Eigen::Vector3d& sun) {
  const std::vector<ShadowBox> all = WithBounds(boxes);
  ShadowFrame f;
  f.count = static_cast<int>(all.size());
  const Eigen::Matrix4d world_from_eye = view.inverse();
  for (const ShadowBox& b : all) {
    Eigen::Isometry3d T_world_box = T_world_body;
    T_world_box.translation() += T_world_body.linear() * b.center_m;
    const Eigen::Matrix4f box_from_eye =
        (T_world_box.inverse().matrix() * world_from_eye).cast<float>();
    f.box_from_eye.insert(f.box_from_eye.end(), box_from_eye.data(), box_from_eye.data() + 16);
    for (int i = 0; i < 3; ++i) f.half_m.push_back(static_cast<float>(0.5 * b.size_m[i]));
    const Eigen::Vector3d s = T_world_box.linear().transpose() * sun;
    for (int i = 0; i < 3; ++i) f.sun_box.push_back(static_cast<float>(s[i]));
  }
  return f;
}

double RobotSunlit(const std::vector<ShadowBox>& boxes, const Eigen::Isometry3d& T_world_body,
                   const Eigen::Vector3d& sun, const Eigen::Vector3d& p) {
  const std::vector<ShadowBox> all = WithBounds(boxes);
  double lit = 1.0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    Eigen::Isometry3d T_world_box = T_world_body;
    T_world_box.translation() += T_world_body.linear() * all[k].center_m;
    const Eigen::Vector3d q = T_world_box.inverse() * p;
    const Eigen::Vector3d d = T_world_box.linear().transpose() * sun;
    const double along = -q.dot(d);  // to the box's centre along the ray
    const double w = kSunAngularRadiusRad * std::max(along, 0.0) + 1e-4;
    if (k == 0) {
      // Clear of the bounds grown by w along their axes (inside a sphere √3 w wider
      // than theirs): clear of every box. The sphere first, the box if need be.
      const double r = 0.5 * all[k].size_m.norm() + std::sqrt(3.0) * w;
      if (along < -r || q.squaredNorm() - along * along > r * r) return 1.0;
      if (Growth(0.5 * all[k].size_m, q, d) >= w) return 1.0;
      continue;
    }
    const double s = GlslSmoothstep(-w, w, Growth(0.5 * all[k].size_m, q, d));
    lit *= s;
  }
  return lit;
}

const char* RobotShadowShaderSource() {
  return R"(
uniform mat4 caster_from_eye[MAX_CASTERS];
uniform vec3 caster_half[MAX_CASTERS];
uniform vec3 caster_sun[MAX_CASTERS];
uniform int caster_count;

// The least growth of box k at which the ray from `p` (its axes) towards the sun meets
// it: the terms of every pair of axes (i, j) three at a time, no component indexed in a
// loop (llvmpipe runs such loops slowly).
float CasterGrowth(int k, vec3 p) {
  vec3 d = caster_sun[k];
  vec3 s = vec3(d.x < 0.0 ? -1.0 : 1.0, d.y < 0.0 ? -1.0 : 1.0, d.z < 0.0 ? -1.0 : 1.0);
  vec3 ad = max(abs(d), vec3(1e-6));
  vec3 a = -caster_half[k] - p * s;
  vec3 b = caster_half[k] - p * s;
  vec3 tx = (a.x * ad - b * ad.x) / (ad.x + ad);
  vec3 ty = (a.y * ad - b * ad.y) / (ad.y + ad);
  vec3 tz = (a.z * ad - b * ad.z) / (ad.z + ad);
  vec3 m = max(max(max(tx, ty), tz), -b);
  return max(max(m.x, m.y), m.z);
}

float RobotSunlit(vec3 eye) {
  // The bounds first: a ray clear of their sphere grown by √3 w, or of them grown by w,
  // is clear of every box.
  vec3 p = (caster_from_eye[0] * vec4(eye, 1.0)).xyz;
  float along = -dot(p, caster_sun[0]);
  float w = SUN_RADIUS * max(along, 0.0) + 1e-4;
  float r = length(caster_half[0]) + 1.7320508 * w;
  if (along < -r || dot(p, p) - along * along > r * r) return 1.0;
  if (CasterGrowth(0, p) >= w) return 1.0;
  float lit = 1.0;
  for (int k = 1; k < caster_count; ++k) {
    p = (caster_from_eye[k] * vec4(eye, 1.0)).xyz;
    w = SUN_RADIUS * max(-dot(p, caster_sun[k]), 0.0) + 1e-4;
    lit *= smoothstep(-w, w, CasterGrowth(k, p));
  }
  return lit;
}
)";
}

}  // namespace trackbed::render
