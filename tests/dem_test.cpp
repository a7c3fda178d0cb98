// Terrain from a digital elevation model: the grid's interpolation, GeoTIFF and ASCII
// grids of both pixel conventions written here through GDAL and read back at their
// pixel centres, the errors a user meets, and a scenario's check of the cover.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/assets/dem_reader.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/elevation_grid.h"
#include "trackbed/sim/terrain.h"

#ifdef TRACKBED_HAVE_GDAL
#include <cpl_conv.h>
#include <ogr_srs_api.h>

#include "dem_files.h"
#endif

namespace trackbed {
namespace {

namespace fs = std::filesystem;

TEST(ElevationGridTest, IsExactAtSamplesAndBilinearBetween) {
  // 3 × 2 samples, 2 m apart along x, 4 m along y, from (-1, 10).
  const sim::ElevationGrid g(3, 2, {-1.0, 10.0}, {2.0, 4.0}, {0.0, 1.0, 3.0, 4.0, 5.0, 11.0});
  EXPECT_DOUBLE_EQ(g.Height(-1.0, 10.0), 0.0);
  EXPECT_DOUBLE_EQ(g.Height(3.0, 14.0), 11.0);
  EXPECT_DOUBLE_EQ(g.Height(0.0, 10.0), 0.5);   // halfway along the first row
  EXPECT_DOUBLE_EQ(g.Height(-1.0, 12.0), 2.0);  // halfway up the first column
  EXPECT_DOUBLE_EQ(g.Height(2.0, 12.0), 0.25 * (1.0 + 3.0 + 5.0 + 11.0));
  EXPECT_DOUBLE_EQ(g.Height(10.0, 20.0), 11.0);  // beyond: the nearest edge
  EXPECT_TRUE(g.Covers(-1.0, 10.0, 3.0, 14.0));
  EXPECT_FALSE(g.Covers(-1.0, 10.0, 3.1, 14.0));
  EXPECT_DOUBLE_EQ(g.min_height_m(), 0.0);
  EXPECT_DOUBLE_EQ(g.max_height_m(), 11.0);
  EXPECT_THROW(sim::ElevationGrid(1, 2, {0, 0}, {1, 1}, {0, 0}), std::invalid_argument);
  EXPECT_THROW(sim::ElevationGrid(2, 2, {0, 0}, {1, 1}, {0, 0, NAN, 0}), std::invalid_argument);
}

TEST(ElevationGridTest, TerrainHeightsAreTheModelsPlusTheRoughness) {
  sim::TerrainOptions o;
  o.extent_m = {-2.0, -2.0, 2.0, 2.0};
  o.cell_size_m = 0.5;
  std::vector<double> h;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) h.push_back(0.3 * c - 0.1 * r * r);
  }
  auto base = std::make_shared<const sim::ElevationGrid>(6, 6, Eigen::Vector2d(-2.5, -2.5),
                                                         Eigen::Vector2d(1.0, 1.0), h);
  const sim::Terrain flat(o, 7, base);
  for (int j = 0; j < flat.rows(); ++j) {
    for (int i = 0; i < flat.cols(); ++i) {
      const double x = -2.0 + 0.5 * i, y = -2.0 + 0.5 * j;
      ASSERT_DOUBLE_EQ(flat.VertexHeight(i, j), base->Height(x, y)) << i << ", " << j;
    }
  }
  EXPECT_LE(flat.min_height_bound_m(), base->min_height_m());
  EXPECT_GE(flat.max_height_bound_m(), base->max_height_m());
  o.roughness.bump_amplitude_m = 0.05;
  const sim::Terrain rough(o, 7, base), alone(o, 7);
  EXPECT_DOUBLE_EQ(rough.VertexHeight(3, 5), base->Height(-0.5, 0.5) + alone.VertexHeight(3, 5));
  // A model that does not reach the grid's far side is refused.
  o.extent_m = {-2.0, -2.0, 2.8, 2.0};
  EXPECT_THROW(sim::Terrain(o, 7, base), OptionError);
}

#ifdef TRACKBED_HAVE_GDAL

using test_dem::FileHeight;
using test_dem::kEast;
using test_dem::kNorth;
using test_dem::kPixel;
using test_dem::kUtm33n;
using test_dem::WriteGeoTiff;

sim::DemOptions Dem(const fs::path& file, double east, double north) {
  sim::DemOptions o;
  o.file = file.string();
  o.origin_m = {east, north};
  return o;
}

// Every pixel centre inside the read window carries the file's height, less the
// origin's, at the place the file's convention puts it.
void ExpectHeightsAtPixelCentres(const sim::DemOptions& dem, double centre_offset) {
  double at_origin = 0.0;
  const auto g = assets::ReadDem(dem, Eigen::Vector4d(-20.0, -20.0, 20.0, 20.0), &at_origin);
  int checked = 0;
  for (int r = 0; r < 9; ++r) {
    for (int c = 0; c < 12; ++c) {
      const double x = kEast + (c + centre_offset) * kPixel - dem.origin_m.x();
      const double y = kNorth - (r + centre_offset) * kPixel - dem.origin_m.y();
      if (!g->Covers(x, y, x, y)) continue;
      EXPECT_NEAR(g->Height(x, y) + at_origin, static_cast<float>(FileHeight(c, r)), 1e-3)
          << "pixel " << c << ", " << r;
      ++checked;
    }
  }
  EXPECT_GE(checked, 25);
}

TEST(DemReaderTest, GeoTiffAreaPixelsHoldTheirHeightsAtTheirCentres) {
  const fs::path file = WriteGeoTiff("dem_area.tif", false);
  // The origin at pixel (6, 4)'s centre: its height is z = 0.
  const sim::DemOptions dem = Dem(file, kEast + 6.5 * kPixel, kNorth - 4.5 * kPixel);
  const assets::DemHeader h = assets::ReadDemHeader(dem);
  EXPECT_FALSE(h.pixel_is_point);
  EXPECT_EQ(h.driver, "GTiff");
  EXPECT_NEAR(h.first_m.x(), -6.0 * kPixel, 1e-9);
  EXPECT_NEAR(h.last_m.y(), 4.0 * kPixel, 1e-9);
  ExpectHeightsAtPixelCentres(dem, 0.5);
  double at_origin = 0.0;
  const auto g = assets::ReadDem(dem, Eigen::Vector4d(-5, -5, 5, 5), &at_origin);
  EXPECT_NEAR(at_origin, static_cast<float>(FileHeight(6, 4)), 1e-6);
  EXPECT_NEAR(g->Height(0.0, 0.0), 0.0, 1e-12);
}

TEST(DemReaderTest, GeoTiffPointPixelsHoldTheirHeightsAtTheTiePoints) {
  const fs::path file = WriteGeoTiff("dem_point.tif", true);
  const sim::DemOptions dem = Dem(file, kEast + 6.0 * kPixel, kNorth - 4.0 * kPixel);
  const assets::DemHeader h = assets::ReadDemHeader(dem);
  EXPECT_TRUE(h.pixel_is_point);
  EXPECT_NEAR(h.first_m.x(), -6.0 * kPixel, 1e-9);  // pixel (0, 0) at the tie point
  ExpectHeightsAtPixelCentres(dem, 0.0);
}

std::string Utm33nWkt() {
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, kUtm33n);
  char* wkt = nullptr;
  OSRExportToWkt(srs, &wkt);
  const std::string text = wkt;
  CPLFree(wkt);
  OSRDestroySpatialReference(srs);
  return text;
}

TEST(DemReaderTest, AsciiGridCornerAndCentreConventionsAgree) {
  const fs::path dir = testing::TempDir();
  const std::string wkt = Utm33nWkt();
  for (const std::string corner : {"corner", "center"}) {
    std::ofstream(dir / ("grid_" + corner + ".prj")) << wkt;
    std::ofstream f(dir / ("grid_" + corner + ".asc"));
    f.precision(12);
    const double shift = corner == "corner" ? 0.0 : 0.5 * kPixel;
    f << "ncols 12\nnrows 9\nxll" << corner << " " << kEast + shift << "\nyll" << corner << " "
      << kNorth - 9 * kPixel + shift << "\ncellsize " << kPixel << "\n";
    for (int r = 0; r < 9; ++r) {
      for (int c = 0; c < 12; ++c) f << FileHeight(c, r) << (c == 11 ? "\n" : " ");
    }
  }
  // Both describe the same pixels: their centres half a pixel in from the corner.
  for (const char* name : {"grid_corner.asc", "grid_center.asc"}) {
    const sim::DemOptions dem = Dem(dir / name, kEast + 6.5 * kPixel, kNorth - 4.5 * kPixel);
    EXPECT_EQ(assets::ReadDemHeader(dem).driver, "AAIGrid") << name;
    ExpectHeightsAtPixelCentres(dem, 0.5);
  }
}

void ExpectError(const sim::DemOptions& dem, const std::string& what) {
  try {
    assets::ReadDem(dem, Eigen::Vector4d(-20, -20, 20, 20));
    ADD_FAILURE() << "no error for " << dem.file;
  } catch (const assets::AssetError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(dem.file), std::string::npos) << m;
    EXPECT_NE(m.find(what), std::string::npos) << m;
  }
}

TEST(DemReaderTest, ErrorsNameTheFileAndTheProblem) {
  const double e = kEast + 60.0, n = kNorth - 40.0;
  ExpectError(Dem(WriteGeoTiff("dem_degrees.tif", false, 4326), e, n), "is not projected");
  ExpectError(Dem(WriteGeoTiff("dem_no_crs.tif", false, 0), e, n), "has no coordinate system");
  ExpectError(Dem(WriteGeoTiff("dem_hole.tif", false, kUtm33n, true), e, n),
              "pixel (5, 4) has no height");
  ExpectError(Dem(WriteGeoTiff("dem_far.tif", false), e + 1000.0, n), "lies outside");
  const fs::path ok = WriteGeoTiff("dem_ok.tif", false);
  try {
    assets::ReadDem(Dem(ok, e, n), Eigen::Vector4d(-20, -20, 80, 20));
    ADD_FAILURE() << "a terrain beyond the model was read";
  } catch (const assets::AssetError& err) {
    EXPECT_NE(std::string(err.what()).find("short of the terrain's"), std::string::npos);
  }
  ExpectError(Dem("/vsicurl/https://example.org/dem.tif", e, n), "network and virtual paths");
  // 1 mm pixels over the terrain's 40 m × 40 m: 1.6 billion of them, refused before
  // reading (the file is sparse: its pixels are never written).
  const fs::path fine = fs::path(testing::TempDir()) / "dem_fine.tif";
  {
    const char* sparse[] = {"SPARSE_OK=TRUE", "TILED=YES", nullptr};
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), fine.c_str(), 100000, 100000, 1,
                                 GDT_Float32, const_cast<char**>(sparse));
    double gt[6] = {0.0, 0.001, 0.0, 100.0, 0.0, -0.001};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, kUtm33n);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    GDALClose(ds);
  }
  ExpectError(Dem(fine, 50.0, 50.0), "more than 64 million");
  // An ASCII grid whose header declares 2.5 million rows and whose file ends after two.
  const fs::path short_grid = fs::path(testing::TempDir()) / "dem_short.asc";
  std::ofstream(short_grid.string().substr(0, short_grid.string().size() - 3) + "prj")
      << Utm33nWkt();
  std::ofstream(short_grid) << "ncols 5\nnrows 2500000\nxllcorner " << kEast << "\nyllcorner "
                            << kNorth << "\ncellsize 30\n1 2 3 4 5\n6 7 8 9 10\n";
  ExpectError(Dem(short_grid, kEast + 60.0, kNorth + 60.0),
              "declares 5 × 2500000 heights, more than its");
  const fs::path text = fs::path(testing::TempDir()) / "dem_text.tif";
  std::ofstream(text) << "not a raster\n";
  ExpectError(Dem(text, e, n), "not a raster");
  ExpectError(Dem(fs::path(testing::TempDir()) / "missing.tif", e, n), "not a raster");
}

TEST(DemReaderTest, AScenarioWhoseTerrainOutrunsTheModelNamesTheKeyAndTheFile) {
  const fs::path tif = WriteGeoTiff("dem_scene.tif", false);
  const fs::path yaml = fs::path(testing::TempDir()) / "dem_scene.yaml";
  const std::string drive = "drive:\n  waypoints: [[0, 0], [10, 0]]\n";
  std::ofstream(yaml) << std::setprecision(12) << drive
                      << "scene:\n  terrain:\n    extent_m: [-30, -20, 60, 20]\n"
                      << "    dem: {file: dem_scene.tif, origin: [" << kEast + 60.0 << ", "
                      << kNorth - 40.0 << "]}\n";
  try {
    scenario::LoadScenario(yaml.string());
    ADD_FAILURE() << "no error";
  } catch (const scenario::ScenarioError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("dem_scene.yaml"), std::string::npos) << m;
    EXPECT_NE(m.find("scene.terrain.dem.file"), std::string::npos) << m;
    EXPECT_NE(m.find(tif.string()), std::string::npos) << m;
    EXPECT_NE(m.find("short of the terrain's grid"), std::string::npos) << m;
  }
  std::ofstream(yaml) << std::setprecision(12) << drive
                      << "scene:\n  terrain:\n    extent_m: [-30, -20, 30, 20]\n"
                      << "    dem: {file: dem_scene.tif, origin: [" << kEast + 60.0 << ", "
                      << kNorth - 40.0 << "]}\n";
  const scenario::Scenario s = scenario::LoadScenario(yaml.string());
  EXPECT_EQ(s.scene.terrain.dem.file, tif.string());  // resolved against the scenario's folder
}

#else

TEST(DemReaderTest, WithoutGdalAScenarioNamingAModelIsRefused) {
  EXPECT_FALSE(assets::CanReadDems());
  sim::DemOptions dem;
  dem.file = "field.tif";
  try {
    assets::ReadDem(dem, Eigen::Vector4d(-1, -1, 1, 1));
    ADD_FAILURE() << "no error";
  } catch (const assets::AssetError& e) {
    EXPECT_NE(std::string(e.what()).find("field.tif: this trackbed was built without GDAL"),
              std::string::npos)
        << e.what();
  }
  GTEST_SKIP() << "built without GDAL (TRACKBED_WITH_GDAL=OFF): models are not written or read";
}

#endif

}  // namespace
}  // namespace trackbed
