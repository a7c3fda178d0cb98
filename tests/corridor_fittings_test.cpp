// Corridor fittings (sim/corridor_fittings.h, `scene.fittings`): on the shipped fitted
// corridor every fitting has its cited size and mounting height and lies on a wall face
// that looks onto the route, clear of doors and of each other; the same seed places the
// same, another elsewhere; and a bad `scene.fittings` names the file, the key and why.
#include "trackbed/sim/corridor_fittings.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scenario_error_of.h"

namespace trackbed::sim {
namespace {

namespace fs = fitting_size;

scenario::Scenario Fitted(std::uint64_t seed) {
  scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/corridor_fitted.yaml");
  s.seed = seed;
  return s;
}

// The fittings: the scene's objects beyond those its file lists.
std::vector<StaticObject> Fittings(const scenario::Scenario& s) {
  const std::vector<StaticObject> all = scenario::SceneObjects(s);
  return {all.begin() + static_cast<long>(s.scene.objects.size()), all.end()};
}

std::map<std::string, int> CountByKind(const std::vector<StaticObject>& objects) {
  std::map<std::string, int> n;
  for (const StaticObject& o : objects) ++n[o.kind];
  return n;
}

// Distance from a point to the corridor's route (the shipped corridor's centreline).
double RouteDistance(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& route) {
  double best = 1e9;
  for (std::size_t k = 1; k < route.size(); ++k) {
    const Eigen::Vector2d d = route[k] - route[k - 1];
    const double t = std::clamp((p - route[k - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (route[k - 1] + t * d - p).norm());
  }
  return best;
}

TEST(CorridorFittingsTest, FittingsHaveTheirCitedSizesAndSitOnTheWallsFacingTheRoute) {
  const scenario::Scenario s = Fitted(1);
  const std::vector<StaticObject> fittings = Fittings(s);
  const std::map<std::string, int> n = CountByKind(fittings);
  // Five doors, each on a fitted face: three frame pieces each and a switch beside it.
  EXPECT_EQ(n.at("door_frame"), 15);
  EXPECT_EQ(n.at("switch_plate"), 5);
  // Ceiling lights every 2.5 m along the 40 m route, the first 1.25 m from its start.
  EXPECT_EQ(n.at("luminaire"), 16);
  EXPECT_GE(n.at("radiator"), 1);
  EXPECT_GE(n.at("notice_board"), 1);
  EXPECT_GE(n.at("extinguisher"), 1);
  EXPECT_GE(n.at("skirting"), 6);
  const std::vector<Eigen::Vector2d>& route = s.drive.waypoints;
  // The corridor is 2 m wide between the faces: a fitting d out of a wall has its centre
  // 1 - d from the centreline (the L's corner aside, where both legs' faces are near).
  const auto on_face = [&](const StaticObject& o, double out_of_wall) {
    return std::abs(RouteDistance(o.center_m, route) - (1.0 - out_of_wall)) < 1e-9;
  };
  for (const StaticObject& o : fittings) {
    SCOPED_TRACE(o.kind);
    if (o.kind == "skirting") {
      EXPECT_DOUBLE_EQ(o.size_m.z(), fs::kSkirtingHeightM);
      EXPECT_DOUBLE_EQ(o.size_m.y(), fs::kSkirtingThicknessM);
      EXPECT_DOUBLE_EQ(o.base_z_m, 0.0);
      EXPECT_FALSE(o.collides);
    } else if (o.kind == "switch_plate") {
      EXPECT_NEAR(o.base_z_m + 0.5 * o.size_m.z(), fs::kSwitchCentreHeightM, 1e-12);
      EXPECT_DOUBLE_EQ(o.size_m.x(), fs::kSwitchPlateM);
      EXPECT_TRUE(on_face(o, 0.5 * fs::kSwitchDepthM));
    } else if (o.kind == "luminaire") {
      EXPECT_NEAR(RouteDistance(o.center_m, route), 0.0, 1e-12);
      EXPECT_NEAR(o.base_z_m + o.size_m.z(), s.scene.appearance.ceiling_height_m, 1e-12);
      EXPECT_DOUBLE_EQ(o.size_m.x(), fs::kLuminaireSideM);
    } else if (o.kind == "radiator") {
      EXPECT_TRUE(o.collides);
      EXPECT_DOUBLE_EQ(o.size_m.z(), fs::kRadiatorHeightM);
      EXPECT_DOUBLE_EQ(o.base_z_m, fs::kRadiatorFloorGapM);
      EXPECT_NE(std::find(std::begin(fs::kRadiatorLengthsM), std::end(fs::kRadiatorLengthsM),
                          o.size_m.x()),
                std::end(fs::kRadiatorLengthsM));
      EXPECT_TRUE(on_face(o, fs::kRadiatorWallGapM + 0.5 * fs::kRadiatorDepthM));
    } else if (o.kind == "notice_board") {
      EXPECT_NEAR(o.base_z_m + 0.5 * o.size_m.z(), fs::kBoardCentreHeightM, 1e-12);
      EXPECT_TRUE(on_face(o, 0.5 * fs::kBoardDepthM));
    } else if (o.kind == "extinguisher") {
      EXPECT_TRUE(o.collides);
      EXPECT_NEAR(o.base_z_m + o.height_m, fs::kExtinguisherTopM, 1e-12);
      EXPECT_TRUE(on_face(o, fs::kExtinguisherWallGapM + fs::kExtinguisherRadiusM));
    }
  }
}

TEST(CorridorFittingsTest, FramesSurroundTheDoorsAndTheSkirtingStopsAtThem) {
  const scenario::Scenario s = Fitted(1);
  const std::vector<StaticObject> fittings = Fittings(s);
  for (const StaticObject& door : s.scene.objects) {
    if (door.kind != "door") continue;
    const Eigen::Vector2d along(std::cos(door.yaw_rad), std::sin(door.yaw_rad));
    int jambs = 0;
    for (const StaticObject& o : fittings) {
      const double s_along = (o.center_m - door.center_m).dot(along);
      const double across =
          std::abs((o.center_m - door.center_m).dot(Eigen::Vector2d(-along.y(), along.x())));
      if (across > 0.1) continue;  // not on this door's face
      if (o.kind == "door_frame" && o.size_m.z() > 1.0 && std::abs(s_along) < door.size_m.x()) {
        // A jamb: its inner edge on the leaf's edge, as high as the leaf.
        EXPECT_NEAR(std::abs(s_along) - 0.5 * o.size_m.x(), 0.5 * door.size_m.x(), 1e-9);
        EXPECT_DOUBLE_EQ(o.size_m.z(), door.size_m.z());
        ++jambs;
      }
      if (o.kind == "skirting") {
        // No skirting across the door and its frame.
        const double reach = 0.5 * door.size_m.x() + fs::kFrameFaceM - 1e-9;
        EXPECT_TRUE(s_along + 0.5 * o.size_m.x() <= -reach ||
                    s_along - 0.5 * o.size_m.x() >= reach);
      }
    }
    EXPECT_EQ(jambs, 2);
  }
}

TEST(CorridorFittingsTest, WallFittingsKeepClearOfDoorsPostersAndEachOther) {
  for (std::uint64_t seed : {1, 2, 3, 4, 5}) {
    const scenario::Scenario s = Fitted(seed);
    std::vector<StaticObject> placed = Fittings(s);
    std::vector<StaticObject> fixed;
    for (const StaticObject& o : s.scene.objects) {
      if (o.kind == "door" || o.kind == "poster") fixed.push_back(o);
    }
    const auto half = [](const StaticObject& o) {
      return o.shape == StaticObject::Shape::kBox ? 0.5 * o.size_m.x() : o.radius_m;
    };
    const auto is_wall_fitting = [](const StaticObject& o) {
      return o.kind == "radiator" || o.kind == "notice_board" || o.kind == "extinguisher";
    };
    for (std::size_t a = 0; a < placed.size(); ++a) {
      if (!is_wall_fitting(placed[a])) continue;
      // No closer along the wall than their half widths and the gap.
      for (const StaticObject& b : fixed) {
        EXPECT_GE((placed[a].center_m - b.center_m).norm(),
                  half(placed[a]) + half(b) + fs::kFittingGapM - 0.15)
            << placed[a].kind << " seed " << seed;
      }
      for (std::size_t b = a + 1; b < placed.size(); ++b) {
        if (!is_wall_fitting(placed[b])) continue;
        EXPECT_GE((placed[a].center_m - placed[b].center_m).norm(),
                  half(placed[a]) + half(placed[b]) + fs::kFittingGapM - 0.15)
            << placed[a].kind << " and " << placed[b].kind << " seed " << seed;
      }
      // Obstacles leave the robot the corridor's middle: 0.8 m and more from the route.
      EXPECT_GT(RouteDistance(placed[a].center_m, s.drive.waypoints), 0.8);
    }
  }
}

TEST(CorridorFittingsTest, TheSameSeedPlacesTheSameAndAnotherElsewhere) {
  const std::vector<StaticObject> a = Fittings(Fitted(7)), b = Fittings(Fitted(7));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].kind, b[k].kind);
    EXPECT_EQ(a[k].center_m, b[k].center_m);  // bit for bit
    EXPECT_EQ(a[k].size_m, b[k].size_m);
    EXPECT_EQ(a[k].base_z_m, b[k].base_z_m);
  }
  const std::vector<StaticObject> c = Fittings(Fitted(8));
  int moved = 0;
  for (const StaticObject& o : c) {
    if (o.kind != "radiator" && o.kind != "notice_board" && o.kind != "extinguisher") continue;
    const bool same = std::any_of(a.begin(), a.end(), [&](const StaticObject& p) {
      return p.kind == o.kind && p.center_m == o.center_m;
    });
    moved += !same;
  }
  EXPECT_GT(moved, 0);
}

using scenario::test::ErrorOf;

TEST(CorridorFittingsTest, BadFittingsKeysNameTheFileTheKeyAndTheReason) {
  const std::string drive = "drive:\n  waypoints: [[0, 0], [5, 0]]\n";
  const std::string ceiling = "  appearance: {ceiling_height_m: 2.5}\n";
  EXPECT_EQ(ErrorOf(drive + "scene:\n  fittings: {light_spacing_m: 0}\n" + ceiling),
            "test.yaml: scene.fittings.light_spacing_m: must be > 0 (got 0)");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  fittings: {radiator_spacing_m: -2}\n" + ceiling),
            "test.yaml: scene.fittings.radiator_spacing_m: must be > 0 (got -2)");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  fittings: {}\n"),
            "test.yaml: scene.fittings.ceiling_lights: needs a ceiling "
            "(scene.appearance.ceiling_height_m > 0)");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  fittings: {ceiling_lights: false}\n"), "");
  EXPECT_EQ(ErrorOf(drive + "scene:\n  fittings: {radiators: maybe}\n" + ceiling)
                .rfind("test.yaml: scene.fittings.radiators: ", 0),
            0u);
  EXPECT_EQ(ErrorOf(drive + "scene:\n  fittings: {radiatorz: true}\n" + ceiling)
                .rfind("test.yaml: scene.fittings.radiatorz: ", 0),
            0u);
  EXPECT_EQ(
      ErrorOf("drive: {mode: script, script: [{t_s: 0, v_mps: 0.2}]}\nscene:\n  fittings: {}\n" +
              ceiling),
      "test.yaml: scene.fittings: needs drive.waypoints: the fittings face the route");
}

TEST(CorridorFittingsTest, WithoutTheSectionTheSceneHasNoFittings) {
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/corridor.yaml");
  EXPECT_FALSE(s.scene.fittings.has_value());
  EXPECT_EQ(scenario::SceneObjects(s).size(), s.scene.objects.size());
  // And the resolved scenario is written without the key.
  EXPECT_EQ(scenario::ScenarioToYaml(s).find("fittings"), std::string::npos);
}

}  // namespace
}  // namespace trackbed::sim
