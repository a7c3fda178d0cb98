// A parked car's parts (see car_model.h). Shares of the length and the height that the
// sources above do not give are authored from the reference car's side view: the
// front overhang 0.205 and the rear 0.175 of the length (together the length less the
// wheelbase), the ground clearance 0.14 m, the belt line at 0.67 of the height, the
// glasshouse from 0.47 of the length behind the centre to 0.20 ahead of it at the belt
// and from 0.42 behind to the centre at the roof, 0.05 m in from the sides at the belt
// and 0.17 m at the roof; lamps 0.30 × 0.12 m.
#include "trackbed/render/car_model.h"

#include <algorithm>
#include <tuple>

namespace trackbed::render {

Eigen::Vector3d CarPart::Min() const {
  if (shape == Shape::kWheel) {
    const double inner = center.y() - side * width;
    return {center.x() - radius, std::min(center.y(), inner), center.z() - radius};
  }
  return {std::min(x0, top_x0), -std::max(half_width, top_half_width), z0};
}

Eigen::Vector3d CarPart::Max() const {
  if (shape == Shape::kWheel) {
    const double inner = center.y() - side * width;
    return {center.x() + radius, std::max(center.y(), inner), center.z() + radius};
  }
  return {std::max(x1, top_x1), std::max(half_width, top_half_width), z1};
}

namespace {

CarPart Box(const std::string& appearance, double albedo, double x0, double x1, double half_width,
            double z0, double z1) {
  CarPart p;
  p.appearance = appearance;
  p.albedo = albedo;
  p.x0 = p.top_x0 = x0;
  p.x1 = p.top_x1 = x1;
  p.half_width = p.top_half_width = half_width;
  p.z0 = z0;
  p.z1 = z1;
  return p;
}

}  // namespace

std::vector<CarPart> CarParts(const Eigen::Vector3d& size_m) {
  const double L = size_m.x(), W = size_m.y(), H = size_m.z();
  const double half_l = 0.5 * L, half_w = 0.5 * W;
  const double wheel_r = 0.5 * kCarWheelDiameterM;
  const double front_axle = half_l - 0.205 * L;
  const double rear_axle = -half_l + 0.175 * L;
  const double arch_r = wheel_r + 0.05;  // the arch's clearance around the tyre
  const double clearance = 0.14, arch_top = kCarWheelDiameterM + 0.06;
  const double belt = 0.67 * H;
  const double wheel_y = 0.5 * kCarReferenceTrackM / kCarReferenceWidthM * W + 0.5 * kCarTyreWidthM;
  std::vector<CarPart> parts;
  // The body: below the arches' tops between and beyond the wheels, the full length
  // above them; the wheel houses dark between the wheels.
  parts.push_back(Box("", 0, rear_axle + arch_r, front_axle - arch_r, half_w, clearance, arch_top));
  parts.push_back(Box("", 0, front_axle + arch_r, half_l - 0.02, half_w, 0.2, arch_top));
  parts.push_back(Box("", 0, -half_l + 0.02, rear_axle - arch_r, half_w, 0.2, arch_top));
  parts.push_back(Box("", 0, -half_l + 0.02, half_l - 0.02, half_w, arch_top, belt));
  for (const double axle : {rear_axle, front_axle}) {
    parts.push_back(Box("car_underbody", 0.04, axle - arch_r, axle + arch_r,
                        wheel_y - kCarTyreWidthM - 0.02, clearance, arch_top));
  }
  // The glasshouse, the roof on it and a B-pillar through it.
  CarPart glass = Box("car_glass", 0.12, -0.47 * L, 0.20 * L, half_w - 0.05, belt, H - 0.04);
  glass.top_x0 = -0.42 * L;
  glass.top_x1 = 0.0;
  glass.top_half_width = half_w - 0.17;
  parts.push_back(glass);
  parts.push_back(Box("", 0, -0.42 * L - 0.01, 0.01, half_w - 0.16, H - 0.04, H));
  CarPart pillar = glass;
  pillar.appearance = "";
  const double b = -0.14 * L;
  pillar.x0 = pillar.top_x0 = b - 0.05;
  pillar.x1 = pillar.top_x1 = b + 0.05;
  pillar.half_width += 0.005;
  pillar.top_half_width += 0.005;
  parts.push_back(pillar);
  // Lamps across the front and the rear (both lamps of a pair as one slab behind a
  // painted middle), and the plates 20 mm before the bumpers.
  const double lamp_z0 = belt - 0.17, lamp_z1 = belt - 0.05;
  parts.push_back(
      Box("car_lamp", 0.8, half_l - 0.02, half_l - 0.003, half_w - 0.06, lamp_z0, lamp_z1));
  parts.push_back(
      Box("", 0, half_l - 0.015, half_l, half_w - 0.38, lamp_z0 - 0.01, lamp_z1 + 0.01));
  parts.push_back(
      Box("car_tail_lamp", 0.25, -half_l + 0.003, -half_l + 0.02, half_w - 0.06, lamp_z0, lamp_z1));
  parts.push_back(
      Box("", 0, -half_l, -half_l + 0.015, half_w - 0.38, lamp_z0 - 0.01, lamp_z1 + 0.01));
  for (const auto& [x0, x1, z] :
       {std::tuple{half_l - 0.02, half_l, 0.42}, std::tuple{-half_l, -half_l + 0.02, 0.5}}) {
    parts.push_back(Box("car_plate", 0.85, x0, x1, 0.5 * kCarPlateWidthM,
                        z - 0.5 * kCarPlateHeightM, z + 0.5 * kCarPlateHeightM));
  }
  // The wheels: tyres, each with its rim as a disc on its outer face.
  for (const double axle : {rear_axle, front_axle}) {
    for (const int side : {1, -1}) {
      CarPart tyre;
      tyre.shape = CarPart::Shape::kWheel;
      tyre.appearance = "car_tyre";
      tyre.albedo = 0.05;
      tyre.center = {axle, side * (wheel_y - 0.005), wheel_r};
      tyre.radius = wheel_r;
      tyre.width = kCarTyreWidthM - 0.005;
      tyre.side = side;
      parts.push_back(tyre);
      CarPart rim = tyre;
      rim.appearance = "car_rim";
      rim.albedo = 0.55;
      rim.center.y() = side * wheel_y;
      rim.radius = 0.5 * kCarRimDiameterM;
      rim.width = 0.005;
      parts.push_back(rim);
    }
  }
  return parts;
}

}  // namespace trackbed::render
