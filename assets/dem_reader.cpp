// Elevation models read through GDAL's C API (see dem_reader.h).
#include "trackbed/assets/dem_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

namespace trackbed::assets {

namespace {

constexpr const char* kDrivers[] = {"GTiff", "AAIGrid", "EHdr", "ENVI", "HFA", "USGSDEM", nullptr};

[[noreturn]] void Fail(const sim::DemOptions& o, const std::string& what) {
  throw AssetError(o.file + ": " + what);
}

// GDAL's errors kept from its own printing while a file is read; the last one goes
// into our message.
class QuietErrors {
 public:
  QuietErrors() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietErrors() { CPLPopErrorHandler(); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
  static std::string Last() {
    const std::string m = CPLGetLastErrorMsg();
    return m.empty() ? "" : " (" + m + ")";
  }
};

struct DatasetCloser {
  void operator()(void* d) const { GDALClose(static_cast<GDALDatasetH>(d)); }
};
using Dataset = std::unique_ptr<void, DatasetCloser>;

// An open file with its north-up geotransform, pixel centres as GDAL reports them
// whatever the file's pixel convention (GTIFF_POINT_GEO_IGNORE forced off, so that a
// user's setting cannot shift them).
struct OpenDem {
  Dataset dataset;
  double gt[6];
  DemHeader header;
};

// An ASCII grid holds each height as at least one character and a separator: one
// that declares more pixels than its bytes can hold is refused before GDAL reads it
// (GDAL finds a row of such a grid by reading every row before it, one error each).
void CheckTextGridHoldsItsPixels(const sim::DemOptions& o, const DemHeader& h) {
  if (h.driver != "AAIGrid") return;
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(o.file, error);
  const double needed = 2.0 * static_cast<double>(h.cols) * h.rows - 1.0;
  if (!error && static_cast<double>(bytes) < needed) {
    Fail(o, "declares " + std::to_string(h.cols) + " × " + std::to_string(h.rows) +
                " heights, more than its " + std::to_string(bytes) + " bytes can hold");
  }
}

OpenDem Open(const sim::DemOptions& o) {
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
  if (o.file.rfind("/vsi", 0) == 0 || o.file.find("://") != std::string::npos) {
    Fail(o, "network and virtual paths are not read; give a local file");
  }
  QuietErrors quiet;
  CPLSetThreadLocalConfigOption("GTIFF_POINT_GEO_IGNORE", "FALSE");
  OpenDem d;
  d.dataset.reset(
      GDALOpenEx(o.file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, kDrivers, nullptr, nullptr));
  CPLSetThreadLocalConfigOption("GTIFF_POINT_GEO_IGNORE", nullptr);
  if (!d.dataset) {
    Fail(o, "not a raster in one of the formats read (GTiff, AAIGrid, EHdr, ENVI, HFA, USGSDEM)" +
                QuietErrors::Last());
  }
  const GDALDatasetH ds = d.dataset.get();
  if (GDALGetRasterCount(ds) < 1) Fail(o, "has no raster band");
  if (GDALGetGeoTransform(ds, d.gt) != CE_None) Fail(o, "has no georeferencing (geotransform)");
  for (const double g : d.gt) {
    if (!std::isfinite(g)) Fail(o, "has a georeferencing that is not finite");
  }
  if (d.gt[2] != 0.0 || d.gt[4] != 0.0)
    Fail(o, "is rotated or sheared: only north-up grids are read");
  if (!(d.gt[1] > 0.0) || d.gt[5] == 0.0) Fail(o, "has a degenerate pixel size");
  const OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
  if (!srs) Fail(o, "has no coordinate system");
  const char* name = OSRGetName(srs);
  d.header.coordinate_system = name ? name : "";
  if (!OSRIsProjected(srs)) {
    Fail(o, "its coordinate system '" + d.header.coordinate_system +
                "' is not projected: reproject it to one in metres (for example UTM, "
                "`gdalwarp -t_srs EPSG:32633 in.tif out.tif`)");
  }
  if (std::abs(OSRGetLinearUnits(srs, nullptr) - 1.0) > 1e-12) {
    Fail(o, "its coordinate system '" + d.header.coordinate_system + "' is not in metres");
  }
  const char* point = GDALGetMetadataItem(ds, "AREA_OR_POINT", nullptr);
  d.header.pixel_is_point = point && std::string(point) == "Point";
  d.header.driver = GDALGetDriverShortName(GDALGetDatasetDriver(ds));
  d.header.cols = GDALGetRasterXSize(ds);
  d.header.rows = GDALGetRasterYSize(ds);
  char** files = GDALGetFileList(ds);
  for (char** f = files; f && *f; ++f) d.header.files.emplace_back(*f);
  CSLDestroy(files);
  if (d.header.cols < 2 || d.header.rows < 2) Fail(o, "has fewer than 2 × 2 pixels");
  CheckTextGridHoldsItsPixels(o, d.header);
  return d;
}

// World x of pixel column c's centre, world y of pixel row r's centre.
double ColumnX(const OpenDem& d, const sim::DemOptions& o, double c) {
  return (d.gt[0] - o.origin_m.x()) + (c + 0.5) * d.gt[1];
}
double RowY(const OpenDem& d, const sim::DemOptions& o, double r) {
  return (d.gt[3] - o.origin_m.y()) + (r + 0.5) * d.gt[5];
}

void FillHeader(const sim::DemOptions& o, OpenDem* d) {
  DemHeader& h = d->header;
  const double ya = RowY(*d, o, 0), yb = RowY(*d, o, h.rows - 1);
  h.first_m = Eigen::Vector2d(ColumnX(*d, o, 0), std::min(ya, yb));
  h.last_m = Eigen::Vector2d(ColumnX(*d, o, h.cols - 1), std::max(ya, yb));
  h.spacing_m = Eigen::Vector2d(d->gt[1], std::abs(d->gt[5]));
}

// The pixel window [c0, c1] × [r0, r1] whose centres surround [lo, hi] in x and y,
// one more pixel around where the file has it. False where the file does not reach.
bool Window(const OpenDem& d, const sim::DemOptions& o, const Eigen::Vector2d& lo,
            const Eigen::Vector2d& hi, int win[4]) {
  const auto column = [&](double x) { return (x - (d.gt[0] - o.origin_m.x())) / d.gt[1] - 0.5; };
  const auto row = [&](double y) { return (y - (d.gt[3] - o.origin_m.y())) / d.gt[5] - 0.5; };
  const double ca = column(lo.x()), cb = column(hi.x());
  const double ra = row(lo.y()), rb = row(hi.y());
  const double c_lo = std::min(ca, cb), c_hi = std::max(ca, cb);
  const double r_lo = std::min(ra, rb), r_hi = std::max(ra, rb);
  const double tolerance = 1e-9;
  // Written so that a NaN fails it: an origin or box beyond what a double resolves
  // lies outside the file, not at some index.
  if (!(c_lo >= -tolerance && r_lo >= -tolerance && c_hi <= d.header.cols - 1 + tolerance &&
        r_hi <= d.header.rows - 1 + tolerance)) {
    return false;
  }
  win[0] = std::max(0, static_cast<int>(std::floor(c_lo + tolerance)) - 1);
  win[1] = std::min(d.header.cols - 1, static_cast<int>(std::ceil(c_hi - tolerance)) + 1);
  win[2] = std::max(0, static_cast<int>(std::floor(r_lo + tolerance)) - 1);
  win[3] = std::min(d.header.rows - 1, static_cast<int>(std::ceil(r_hi - tolerance)) + 1);
  return true;
}

std::string Describe(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

// The window's heights as an elevation grid in the world frame (first row at the
// lowest y), with the band's scale and offset applied; no-data pixels refused.
sim::ElevationGrid ReadWindow(const OpenDem& d, const sim::DemOptions& o, const int win[4]) {
  const GDALRasterBandH band = GDALGetRasterBand(d.dataset.get(), 1);
  const int nc = win[1] - win[0] + 1, nr = win[3] - win[2] + 1;
  // 64 million pixels (512 MB of heights): a terrain of 10 km a side needs 11 million
  // at 3 m pixels.
  if (static_cast<double>(nc) * nr > 64e6) {
    Fail(o, "the terrain needs " + std::to_string(nc) + " × " + std::to_string(nr) +
                " of its pixels, more than 64 million");
  }
  std::vector<double> file_rows(static_cast<std::size_t>(nc) * static_cast<std::size_t>(nr));
  QuietErrors quiet;
  if (GDALRasterIO(band, GF_Read, win[0], win[2], nc, nr, file_rows.data(), nc, nr, GDT_Float64, 0,
                   0) != CE_None) {
    Fail(o, "its heights cannot be read" + QuietErrors::Last());
  }
  int has_nodata = 0, has_scale = 0, has_offset = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
  const double scale = GDALGetRasterScale(band, &has_scale);
  const double offset = GDALGetRasterOffset(band, &has_offset);
  const std::string unit = GDALGetRasterUnitType(band);
  if (!unit.empty() && unit != "m" && unit != "metre" && unit != "meter" && unit != "metres") {
    Fail(o, "its heights are in '" + unit + "': metres expected");
  }
  const bool flip = d.gt[5] < 0.0;  // the file's first row is the highest y
  std::vector<double> heights(file_rows.size());
  for (int r = 0; r < nr; ++r) {
    for (int c = 0; c < nc; ++c) {
      const double v = file_rows[static_cast<std::size_t>(r) * nc + c];
      if ((has_nodata && v == nodata) || !std::isfinite(v)) {
        Fail(o, "pixel (" + std::to_string(win[0] + c) + ", " + std::to_string(win[2] + r) +
                    ") has no height, and the terrain needs it");
      }
      const double h = v * scale + offset;
      if (!std::isfinite(h)) Fail(o, "a height is not finite after the band's scale and offset");
      const int world_row = flip ? nr - 1 - r : r;
      heights[static_cast<std::size_t>(world_row) * nc + c] = h;
    }
  }
  const double y_first = RowY(d, o, flip ? win[3] : win[2]);
  return sim::ElevationGrid(nc, nr, Eigen::Vector2d(ColumnX(d, o, win[0]), y_first),
                            Eigen::Vector2d(d.gt[1], std::abs(d.gt[5])), std::move(heights));
}

}  // namespace

bool CanReadDems() { return true; }

const char* const* DemDrivers() { return kDrivers; }

DemHeader ReadDemHeader(const sim::DemOptions& options) {
  OpenDem d = Open(options);
  FillHeader(options, &d);
  return d.header;
}

std::shared_ptr<const sim::ElevationGrid> ReadDem(const sim::DemOptions& options,
                                                  const Eigen::Vector4d& extent_m,
                                                  double* height_at_origin_m) {
  OpenDem d = Open(options);
  FillHeader(options, &d);
  int origin_window[4];
  const Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  if (!Window(d, options, origin, origin, origin_window)) {
    Fail(options, "the origin (" + Describe(options.origin_m.x()) + ", " +
                      Describe(options.origin_m.y()) + ") lies outside its pixel centres");
  }
  const double at_origin = ReadWindow(d, options, origin_window).Height(0.0, 0.0);
  int win[4];
  const Eigen::Vector2d lo(extent_m[0], extent_m[1]), hi(extent_m[2], extent_m[3]);
  if (!Window(d, options, lo, hi, win)) {
    const DemHeader& h = d.header;
    Fail(options, "its pixel centres span x " + Describe(h.first_m.x()) + " to " +
                      Describe(h.last_m.x()) + " m and y " + Describe(h.first_m.y()) + " to " +
                      Describe(h.last_m.y()) + " m around the origin, short of the terrain's [" +
                      Describe(lo.x()) + ", " + Describe(lo.y()) + ", " + Describe(hi.x()) + ", " +
                      Describe(hi.y()) + "]");
  }
  const sim::ElevationGrid raw = ReadWindow(d, options, win);
  std::vector<double> heights;
  heights.reserve(static_cast<std::size_t>(raw.cols()) * raw.rows());
  for (int r = 0; r < raw.rows(); ++r) {
    for (int c = 0; c < raw.cols(); ++c) heights.push_back(raw.Sample(c, r) - at_origin);
  }
  if (height_at_origin_m) *height_at_origin_m = at_origin;
  return std::make_shared<const sim::ElevationGrid>(raw.cols(), raw.rows(), raw.first_m(),
                                                    raw.spacing_m(), std::move(heights));
}

}  // namespace trackbed::assets
