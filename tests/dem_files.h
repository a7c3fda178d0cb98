// Elevation models the tests write through GDAL's own API: a GeoTIFF with known
// heights, coordinate system and pixel convention.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

namespace trackbed::test_dem {

// UTM zone 33 N: a projected system in metres.
constexpr int kUtm33n = 32633;
constexpr double kEast = 500000.0, kNorth = 4649776.0, kPixel = 10.0;

inline double FileHeight(int c, int r) { return 120.0 + 0.7 * c - 0.35 * r + 0.05 * c * r; }

// Writes a 12 × 9 GeoTIFF (in the tests' temporary folder) whose top-left pixel's corner (areas) or
// centre (points) is at (kEast, kNorth), the given coordinate system, heights FileHeight; pixel (5,
// 4) has no data where `hole`.
inline std::filesystem::path WriteGeoTiff(const std::string& name, bool points, int epsg = kUtm33n,
                                          bool hole = false) {
  const std::filesystem::path file = std::filesystem::path(testing::TempDir()) / name;
  GDALAllRegister();
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  GDALDatasetH ds = GDALCreate(driver, file.c_str(), 12, 9, 1, GDT_Float32, nullptr);
  // Written as given: the geotransform's origin is the tie point, of a pixel's corner
  // for areas and of its centre for points.
  CPLSetThreadLocalConfigOption("GTIFF_POINT_GEO_IGNORE", "TRUE");
  if (points) GDALSetMetadataItem(ds, "AREA_OR_POINT", "Point", nullptr);
  double gt[6] = {kEast, kPixel, 0.0, kNorth, 0.0, -kPixel};
  GDALSetGeoTransform(ds, gt);
  if (epsg > 0) {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, epsg);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
  }
  std::vector<float> v;
  for (int r = 0; r < 9; ++r) {
    for (int c = 0; c < 12; ++c) v.push_back(static_cast<float>(FileHeight(c, r)));
  }
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  if (hole) {
    GDALSetRasterNoDataValue(band, -9999.0);
    v[4 * 12 + 5] = -9999.0f;
  }
  EXPECT_EQ(GDALRasterIO(band, GF_Write, 0, 0, 12, 9, v.data(), 12, 9, GDT_Float32, 0, 0), CE_None);
  GDALClose(ds);
  CPLSetThreadLocalConfigOption("GTIFF_POINT_GEO_IGNORE", nullptr);
  return file;
}

}  // namespace trackbed::test_dem
