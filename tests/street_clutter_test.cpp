// The street's clutter: a parked car's parts (render/car_model.h) at their cited sizes
// inside the car's box, and the KITTI twin's street as scripts/kitti_twin_scene.py lays
// it out (cars in the parking lanes, clear of the lanes driven and of each other; house
// fronts, doors and downpipes beyond the pavements). The facade texture's layout is
// checked with the other textures (procedural_texture_test.cpp).
#include "trackbed/render/car_model.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facade_texture.h"
#include "trackbed/render/procedural_texture.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::render {
namespace {

TEST(CarModelTest, WheelsAndPlatesHaveTheCitedSizes) {
  // 205/55 R16: 406.4 mm of rim and twice a 112.75 mm sidewall.
  EXPECT_NEAR(kCarWheelDiameterM, 0.6319, 1e-4);
  const std::vector<CarPart> parts = CarParts({4.255, 1.799, 1.452});
  int tyres = 0, rims = 0, plates = 0;
  std::vector<double> axles;
  for (const CarPart& p : parts) {
    if (p.appearance == "car_tyre") {
      ++tyres;
      EXPECT_NEAR(2 * p.radius, kCarWheelDiameterM, 1e-12);
      EXPECT_NEAR(p.center.z() - p.radius, 0.0, 1e-12);  // on the ground
      axles.push_back(p.center.x());
      // The outer faces one track apart plus a tyre's width (Golf VII: 1.549 m).
      EXPECT_NEAR(std::abs(p.center.y()) + 0.005, 0.5 * (1.549 + kCarTyreWidthM), 1e-9);
    } else if (p.appearance == "car_rim") {
      ++rims;
      EXPECT_NEAR(2 * p.radius, 16 * 0.0254, 1e-12);
    } else if (p.appearance == "car_plate") {
      ++plates;
      EXPECT_NEAR(2 * p.half_width, 0.52, 1e-12);
      EXPECT_NEAR(p.z1 - p.z0, 0.11, 1e-12);
    }
  }
  EXPECT_EQ(tyres, 4);
  EXPECT_EQ(rims, 4);
  EXPECT_EQ(plates, 2);
  std::sort(axles.begin(), axles.end());
  axles.erase(std::unique(axles.begin(), axles.end()), axles.end());
  ASSERT_EQ(axles.size(), 2u);
  EXPECT_NEAR(axles[1] - axles[0], 2.637, 0.01);  // the Golf VII's wheelbase
}

TEST(CarModelTest, EveryPartLiesInsideTheCarsBoxAndTheSameSizeGivesTheSameParts) {
  for (const Eigen::Vector3d& size :
       {Eigen::Vector3d(3.8, 1.7, 1.4), Eigen::Vector3d(4.255, 1.799, 1.452),
        Eigen::Vector3d(4.8, 1.9, 1.6)}) {
    const std::vector<CarPart> parts = CarParts(size);
    ASSERT_GE(parts.size(), 20u);
    const Eigen::Vector3d lo(-size.x() / 2, -size.y() / 2, 0.0);
    const Eigen::Vector3d hi(size.x() / 2, size.y() / 2, size.z());
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const CarPart& p = parts[k];
      EXPECT_TRUE((p.Min().array() >= lo.array() - 1e-12).all()) << k << " " << p.appearance;
      EXPECT_TRUE((p.Max().array() <= hi.array() + 1e-12).all()) << k << " " << p.appearance;
      EXPECT_TRUE((p.Max().array() > p.Min().array()).all()) << k;
    }
    const std::vector<CarPart> again = CarParts(size);
    ASSERT_EQ(again.size(), parts.size());
    for (std::size_t k = 0; k < parts.size(); ++k) {
      EXPECT_EQ(again[k].Min(), parts[k].Min());
      EXPECT_EQ(again[k].Max(), parts[k].Max());
      EXPECT_EQ(again[k].appearance, parts[k].appearance);
    }
  }
}

// The runs of texels darker than `below` along row `y`: [first, last] columns.
std::vector<std::pair<int, int>> DarkRuns(const Texture& t, int y, int below) {
  std::vector<std::pair<int, int>> runs;
  for (int x = 0; x < t.size_px; ++x) {
    if (t.at(x, y) >= below) continue;
    if (!runs.empty() && runs.back().second == x - 1) {
      runs.back().second = x;
    } else {
      runs.emplace_back(x, x);
    }
  }
  return runs;
}

// The glass, read along a row just above the panes' foot (below any shutter): two panes
// per window, each window's glass the opening less its frames, one window per bay, the
// same columns a storey higher; the same seed the same bytes, another seed other ones.
TEST(FacadeTextureTest, WindowsHaveTheCitedSizeBayAndStorey) {
  const Texture t = MakeTexture("facade", 3, 512);
  ASSERT_EQ(t.meters_per_repeat, kFacadeTileM);
  const double m = t.meters_per_repeat / t.size_px;  // per texel
  const double foot = kFacadeSillHeightM + kFacadeFrameM + 0.04;
  std::vector<std::vector<std::pair<int, int>>> storeys;
  for (int s = 0; s < 2; ++s) {
    storeys.push_back(DarkRuns(t, static_cast<int>((s * kFacadeStoreyM + foot) / m), 120));
    ASSERT_EQ(storeys.back().size(), 4u) << "storey " << s;  // 2 windows of 2 panes
  }
  EXPECT_EQ(storeys[0], storeys[1]);
  const auto& runs = storeys[0];
  for (int w = 0; w < 2; ++w) {
    const double glass = (runs[2 * w + 1].second + 1 - runs[2 * w].first) * m;
    EXPECT_NEAR(glass, kFacadeWindowWidthM - 2 * kFacadeFrameM, 2 * m) << w;
    const double opening_left = runs[2 * w].first * m - kFacadeFrameM;
    EXPECT_NEAR(opening_left, w * kFacadeBayM + 0.5 * (kFacadeBayM - kFacadeWindowWidthM), 2 * m);
  }
  EXPECT_NEAR((runs[2].first - runs[0].first) * m, kFacadeBayM, 1.5 * m);
  EXPECT_EQ(MakeTexture("facade", 3, 256).texels, MakeTexture("facade", 3, 256).texels);
  EXPECT_NE(MakeTexture("facade", 3, 256).texels, MakeTexture("facade", 4, 256).texels);
}

// The shortest distance from point p to the polyline `path`.
double DistanceToPath(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& path) {
  double best = (p - path.front()).norm();
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const Eigen::Vector2d d = path[k + 1] - path[k];
    const double t = std::clamp((p - path[k]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (path[k] + t * d)).norm());
  }
  return best;
}

TEST(KittiTwinStreetTest, CarsParkInTheirLanesAndHousesStandBeyondThePavements) {
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/kitti_twin.yaml");
  const std::vector<Eigen::Vector2d>& lane = s.drive.waypoints;
  std::vector<const sim::StaticObject*> cars;
  int houses = 0, doors = 0, pipes = 0;
  for (const sim::StaticObject& o : s.scene.objects) {
    const double y = std::abs(o.center_m.y());
    if (o.kind == "car") {
      cars.push_back(&o);
      // Inside the parking lane (the carriageway's outer 2.2 m, |y| 1.8-4.0 m with
      // the kerb at 4 m) and at least 0.3 m from the centreline the camera drives.
      EXPECT_GE(y - o.size_m.y() / 2, 2.0);
      EXPECT_LE(y + o.size_m.y() / 2, 4.1);
      const Eigen::Vector2d inner(o.center_m.x(),
                                  o.center_m.y() - std::copysign(o.size_m.y() / 2, o.center_m.y()));
      EXPECT_GE(DistanceToPath(inner, lane), 0.3);
    } else if (o.kind == "box" && o.size_m.z() > 3.0) {
      ++houses;
      EXPECT_EQ(o.appearance, "facade");
      EXPECT_GE(y - o.size_m.y() / 2, 12.0);  // fronts 12-20 m from the centreline
    } else if (o.kind == "door") {
      ++doors;
      EXPECT_FALSE(o.collides);
      EXPECT_GE(y - o.size_m.y() / 2, 9.0);                           // beyond the pavement
    } else if (o.kind == "post" && std::abs(o.center_m.y()) > 9.0) {  // not a lamp or a sign's
      ++pipes;
      EXPECT_NEAR(o.radius_m, 0.05, 1e-12);  // DN 100
      EXPECT_GE(y - o.radius_m, 9.0);
    }
  }
  EXPECT_GT(cars.size(), 50u);
  EXPECT_GT(houses, 40);
  EXPECT_GT(doors, 40);
  EXPECT_EQ(pipes, 2 * houses);
  // No two parked cars overlap (along the kerb: gaps of at least 0.8 m).
  for (std::size_t i = 0; i < cars.size(); ++i) {
    for (std::size_t j = i + 1; j < cars.size(); ++j) {
      if (cars[i]->center_m.y() * cars[j]->center_m.y() < 0) continue;  // other side
      const double gap = std::abs(cars[i]->center_m.x() - cars[j]->center_m.x()) -
                         0.5 * (cars[i]->size_m.x() + cars[j]->size_m.x());
      EXPECT_GE(gap, 0.79) << i << " " << j;
    }
  }
}

}  // namespace
}  // namespace trackbed::render
