// The robot driven over terrain from a digital elevation model: the GeoTIFF written
// through GDAL, the run through the closed loop, the true path against the model.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "dem_files.h"
#include "trackbed/assets/dem_reader.h"
#include "trackbed/common/sha256.h"
#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/terrain.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

TEST(DemClosedLoopTest, TheTracksClimbTheModelsSlopeAndStayOnIt) {
  test_dem::WriteGeoTiff("dem_drive.tif", false);
  const fs::path dir = fs::path(testing::TempDir()) / "dem_drive";
  const fs::path yaml = fs::path(testing::TempDir()) / "dem_drive.yaml";
  // The origin at pixel (3, 4)'s centre; the drive 8 m east, up the model's 7 % grade.
  std::ofstream(yaml) << std::setprecision(12) << "duration_s: 14\n"
                      << "drive:\n  speed_mps: 0.8\n  waypoints: [[0, 0], [8, 0]]\n"
                      << "scene:\n  terrain:\n    extent_m: [-10, -10, 20, 10]\n"
                      << "    dem: {file: dem_drive.tif, origin: ["
                      << test_dem::kEast + 3.5 * test_dem::kPixel << ", "
                      << test_dem::kNorth - 4.5 * test_dem::kPixel << "]}\n";
  const scenario::Scenario s = scenario::LoadScenario(yaml.string());
  runner::RunToFolder(s, dir);
  const sim::TerrainOptions& t = s.scene.terrain;
  const sim::Terrain terrain(t, 1, assets::ReadDem(t.dem, t.grid_extent_m()));
  std::ifstream tum(dir / "ground_truth.tum");
  std::string line;
  double lo = 1e9, hi = -1e9, x_first = 0.0, x_last = 0.0, z_first = 0.0, z_last = 0.0;
  int rows = 0;
  while (std::getline(tum, line)) {
    std::istringstream in(line);
    double time, x, y, z;
    in >> time >> x >> y >> z;
    const double above = z - terrain.Height(x, y);
    lo = std::min(lo, above);
    hi = std::max(hi, above);
    if (rows++ == 0) x_first = x, z_first = z;
    x_last = x;
    z_last = z;
  }
  ASSERT_GT(rows, 100);
  // The run folder fingerprints the model it read.
  std::ifstream inputs(dir / "inputs.json");
  const std::string text((std::istreambuf_iterator<char>(inputs)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"key\": \"scene.terrain.dem.file\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"sha256\": \"" + Sha256OfFile(t.dem.file) + "\""), std::string::npos)
      << text;
  EXPECT_GT(x_last - x_first, 6.0);  // it drove up the slope
  // The model rises 0.7 m per 10 m pixel eastwards here (and 0.05 m per pixel per row).
  EXPECT_NEAR((z_last - z_first) / (x_last - x_first), 0.07 + 0.005 * 4, 0.01);
  // The body stays at one height above the model's surface: no sinking, no floating.
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi - lo, 0.03) << "height above the ground from " << lo << " to " << hi << " m";
}

// scenes/olinda_dem.yaml on the model Debian's r-cran-stars ships (scripts/setup.sh
// installs it): the terrain's heights at pixel centres are the file's, read here
// through GDAL, less the origin's; the robot drives on them.
TEST(DemClosedLoopTest, TheOlindaExampleStandsOnTheFilesHeights) {
  const std::string file = "/usr/local/share/trackbed/r-cran-stars/tif/olinda_dem_utm25s.tif";
  if (!fs::exists(file)) GTEST_SKIP() << file << " absent (scripts/setup.sh installs it)";
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/olinda_dem.yaml",
                             {scenario::ParseOverride("duration_s=4"),
                              scenario::ParseOverride("robot.stereo.enabled=false")});
  const sim::TerrainOptions& t = s.scene.terrain;
  double at_origin = 0.0;
  const auto model = assets::ReadDem(t.dem, t.grid_extent_m(), &at_origin);
  const sim::Terrain terrain(t, 1, model);
  GDALDatasetH ds = GDALOpen(file.c_str(), GA_ReadOnly);
  ASSERT_NE(ds, nullptr);
  double gt[6];
  ASSERT_EQ(GDALGetGeoTransform(ds, gt), CE_None);
  // Pixels (16..22, 17..23) around the origin, pixel (19, 20)'s centre.
  for (int r = 17; r <= 23; ++r) {
    for (int c = 16; c <= 22; ++c) {
      float h = 0.0f;
      ASSERT_EQ(
          GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, c, r, 1, 1, &h, 1, 1, GDT_Float32, 0, 0),
          CE_None);
      const double x = gt[0] + (c + 0.5) * gt[1] - t.dem.origin_m.x();
      const double y = gt[3] + (r + 0.5) * gt[5] - t.dem.origin_m.y();
      EXPECT_NEAR(model->Height(x, y) + at_origin, h, 1e-3) << "pixel " << c << ", " << r;
    }
  }
  GDALClose(ds);
  const fs::path dir = fs::path(testing::TempDir()) / "dem_olinda";
  runner::RunToFolder(s, dir);
  std::ifstream tum(dir / "ground_truth.tum");
  std::string line;
  double lo = 1e9, hi = -1e9;
  while (std::getline(tum, line)) {
    std::istringstream in(line);
    double time, x, y, z;
    in >> time >> x >> y >> z;
    lo = std::min(lo, z - terrain.Height(x, y));
    hi = std::max(hi, z - terrain.Height(x, y));
  }
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi - lo, 0.05) << "height above the ground from " << lo << " to " << hi << " m";
}

}  // namespace
}  // namespace trackbed
