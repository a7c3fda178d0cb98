// Fuzzes the elevation model reader's mapping of a raster into the world
// (assets/dem_reader.h): the input is written as an ESRI ASCII grid beside a fixed
// projection file (UTM zone 33 N, metres) and read with its header, then for a few
// origins and terrain boxes (the grid's own corner, its centre, far away, tiny and
// huge boxes) into an elevation grid whose heights are queried.
//
// Finding: a crash, a sanitizer report, a hang, or an exception other than the
// documented assets::AssetError; a grid read without error with a height that is
// not finite or outside its samples' range, or a box it does not cover.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>

#include "fuzz_support.h"
#include "trackbed/assets/dem_reader.h"

namespace {

namespace fs = std::filesystem;
using trackbed::fuzz::Finding;

constexpr const char* kTarget = "dem_fuzz";
// EPSG:32633 as ESRI writes it in a .prj file.
constexpr const char* kPrj =
    "PROJCS[\"WGS_1984_UTM_Zone_33N\",GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\","
    "SPHEROID[\"WGS_1984\",6378137.0,298.257223563]],PRIMEM[\"Greenwich\",0.0],"
    "UNIT[\"Degree\",0.0174532925199433]],PROJECTION[\"Transverse_Mercator\"],"
    "PARAMETER[\"False_Easting\",500000.0],PARAMETER[\"False_Northing\",0.0],"
    "PARAMETER[\"Central_Meridian\",15.0],PARAMETER[\"Scale_Factor\",0.9996],"
    "PARAMETER[\"Latitude_Of_Origin\",0.0],UNIT[\"Meter\",1.0]]";

void Read(const trackbed::sim::DemOptions& dem, const Eigen::Vector4d& box) {
  try {
    const auto grid = trackbed::assets::ReadDem(dem, box);
    if (!grid->Covers(box[0], box[1], box[2], box[3])) Finding(kTarget, "the box is not covered");
    for (double u : {0.0, 0.37, 1.0}) {
      for (double v : {0.0, 0.61, 1.0}) {
        const double h =
            grid->Height(box[0] + u * (box[2] - box[0]), box[1] + v * (box[3] - box[1]));
        if (!std::isfinite(h) || h < grid->min_height_m() - 1e-9 * std::abs(grid->min_height_m()) ||
            h > grid->max_height_m() + 1e-9 * std::abs(grid->max_height_m())) {
          Finding(kTarget, "a height outside the samples' range: " + std::to_string(h));
        }
      }
    }
  } catch (const trackbed::assets::AssetError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const trackbed::fuzz::ScratchDir dir("dem");
  const fs::path grid = dir.path / "grid.asc";
  trackbed::fuzz::WriteFile(kTarget, grid, std::string(reinterpret_cast<const char*>(data), size));
  trackbed::fuzz::WriteFile(kTarget, dir.path / "grid.prj", kPrj);
  trackbed::sim::DemOptions dem;
  dem.file = grid.string();
  try {
    const trackbed::assets::DemHeader h = trackbed::assets::ReadDemHeader(dem);
    // Origins at the first pixel centre, the middle of the grid (in the file's
    // coordinates: the header's are relative to the zero origin) and far away.
    const Eigen::Vector2d mid = 0.5 * (h.first_m + h.last_m);
    for (const Eigen::Vector2d& origin : {h.first_m, mid, Eigen::Vector2d(1e7, -1e7)}) {
      dem.origin_m = origin;
      const Eigen::Vector2d a = h.first_m - origin, b = h.last_m - origin;
      Read(dem, Eigen::Vector4d(a.x(), a.y(), b.x(), b.y()));
      Read(dem, Eigen::Vector4d(-0.5, -0.5, 0.5, 0.5));
      Read(dem, Eigen::Vector4d(-1e6, -1e6, 1e6, 1e6));
    }
  } catch (const trackbed::assets::AssetError&) {
  }
  return 0;
}
