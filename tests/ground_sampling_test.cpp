// The ground as a camera samples it: a flat ground carrying stripes along the view,
// seen by the robot's camera (0.5 m up, pitched 5° down, f 381 px), against the same
// view drawn 4 × 4 times as finely and averaged over each pixel — what a sharp camera
// whose pixels integrate over their area sees. At 1, 2, 3 and 5 m the stripes keep
// their contrast (no blur beyond the pixel's footprint) and carry no energy above their
// own frequency that the reference does not (no aliasing). The bounds, 10 % and 4 grey
// levels RMS: docs/results/2026-12-07-ground-sampling.md has what the sampling gives
// and what isotropic mip-mapping gave.
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/sensor_warp.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::render {
namespace {

constexpr int kFactor = 4;         // the reference's render pixels per pixel, each way
constexpr double kHeightM = 0.5;   // the camera above the ground
constexpr double kPitchDeg = 5.0;  // down
constexpr int kStripeTexels = 16;  // period of the stripes: 6.25 cm at 256 texels per metre
constexpr double kTexelsPerM = 256.0;

// Dark and bright stripes along x (the view), kStripeTexels / 2 texels each, 1 m a tile.
Texture Stripes() {
  Texture t;
  t.size_px = 256;
  t.meters_per_repeat = 1.0;
  t.texels.resize(256 * 256);
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) t.texels[y * 256 + x] = (y / (kStripeTexels / 2)) % 2 ? 192 : 64;
  }
  return t;
}

// The camera at (0, 0, kHeightM) looking along +x, pitched down (OpenCV axes).
Eigen::Isometry3d CameraPose() {
  const double p = kPitchDeg * M_PI / 180.0;
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(0, -1, 0);
  R.col(1) = Eigen::Vector3d(-std::sin(p), 0, -std::cos(p));
  R.col(2) = Eigen::Vector3d(std::cos(p), 0, -std::sin(p));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = Eigen::Vector3d(0, 0, kHeightM);
  return T;
}

struct Views {
  geometry::PinholeCamera K;
  GrayImage image;      // as drawn at the camera's size
  GrayImage reference;  // drawn kFactor times as finely, averaged over each pixel
};

Views Render() {
  const sim::World world = test::FlatWorld({}, {-2, -8, 20, 8});
  Views v;
  v.K = robot::StereoRig(robot::StereoRigOptions{}).intrinsics();
  const geometry::PinholeCamera fine = Supersampled(v.K, kFactor);
  Renderer coarse(world, test::AmbientOnly(), {}, 1, v.K.width_px, v.K.height_px, 0.05, 120.0);
  Renderer sharp(world, test::AmbientOnly(), {}, 1, fine.width_px, fine.height_px, 0.05, 120.0);
  for (Renderer* r : {&coarse, &sharp}) r->ReplaceTexture("hard_floor", Stripes());
  coarse.Render(v.K, CameraPose(), 0.0, &v.image, nullptr);
  GrayImage big;
  sharp.Render(fine, CameraPose(), 0.0, &big, nullptr);
  v.reference = v.image;
  for (int y = 0; y < v.K.height_px; ++y) {
    for (int x = 0; x < v.K.width_px; ++x) {
      int sum = 0;
      for (int j = 0; j < kFactor; ++j) {
        for (int i = 0; i < kFactor; ++i) {
          sum +=
              big.pixels[static_cast<std::size_t>((kFactor * y + j) * big.width + kFactor * x + i)];
        }
      }
      v.reference.pixels[static_cast<std::size_t>(y * v.K.width_px + x)] =
          static_cast<std::uint8_t>((sum + kFactor * kFactor / 2) / (kFactor * kFactor));
    }
  }
  return v;
}

constexpr int kBandRows = 5;  // rows about the distance's row
constexpr int kFirstColumn = 64;
constexpr int kColumns = 512;  // the band's columns, about the centre

// The image row where the ground `d` metres ahead is seen.
int RowAt(const geometry::PinholeCamera& K, double d) {
  const Eigen::Vector3d p = CameraPose().inverse() * Eigen::Vector3d(d, 0, 0);
  return static_cast<int>(std::lround(K.Project(p).y()));
}

// A band's rows as doubles, one vector per row.
std::vector<std::vector<double>> Band(const GrayImage& img, int row) {
  std::vector<std::vector<double>> out;
  for (int v = row - kBandRows / 2; v <= row + kBandRows / 2; ++v) {
    std::vector<double> r(kColumns);
    for (int u = 0; u < kColumns; ++u) {
      r[u] = img.pixels[static_cast<std::size_t>(v * img.width + kFirstColumn + u)];
    }
    out.push_back(r);
  }
  return out;
}

// The stripes' contrast in a band: the standard deviation along its rows.
double Contrast(const std::vector<std::vector<double>>& band) {
  double sum = 0.0;
  for (const std::vector<double>& r : band) {
    double mean = 0.0, sq = 0.0;
    for (double x : r) mean += x / r.size();
    for (double x : r) sq += (x - mean) * (x - mean) / r.size();
    sum += std::sqrt(sq);
  }
  return sum / band.size();
}

// RMS [grey levels] of the part of a − b above `cycles` cycles across the band's width.
double EnergyAbove(const std::vector<std::vector<double>>& a,
                   const std::vector<std::vector<double>>& b, double cycles) {
  double energy = 0.0;
  for (std::size_t r = 0; r < a.size(); ++r) {
    for (int k = static_cast<int>(std::ceil(cycles)); k <= kColumns / 2; ++k) {
      std::complex<double> c = 0.0;
      for (int u = 0; u < kColumns; ++u) {
        c += (a[r][u] - b[r][u]) * std::polar(1.0, -2.0 * M_PI * k * u / kColumns);
      }
      energy += (k == kColumns / 2 ? 1.0 : 2.0) * std::norm(c) / (double(kColumns) * kColumns);
    }
  }
  return std::sqrt(energy / a.size());
}

TEST(GroundSamplingTest, StripesKeepTheSharpCamerasContrastWithoutAliasing) {
  const Views v = Render();
  for (const double d : {1.0, 2.0, 3.0, 5.0}) {
    const int row = RowAt(v.K, d);
    const std::vector<std::vector<double>> image = Band(v.image, row);
    const std::vector<std::vector<double>> reference = Band(v.reference, row);
    // The stripes' frequency across the band: the band spans kColumns pixels of
    // ground at depth z along the optical axis.
    const double z = (CameraPose().inverse() * Eigen::Vector3d(d, 0, 0)).z();
    const double period_px = v.K.fx * kStripeTexels / kTexelsPerM / z;
    const double cycles = kColumns / period_px;
    const double contrast = Contrast(image), sharp = Contrast(reference);
    const double aliased = EnergyAbove(image, reference, 1.5 * cycles);
    std::printf(
        "%.0f m: row %d, period %.1f px, contrast %.2f against %.2f (%+.1f %%), "
        "difference above 1.5 f %.2f grey levels\n",
        d, row, period_px, contrast, sharp, 100.0 * (contrast / sharp - 1.0), aliased);
    EXPECT_NEAR(contrast / sharp, 1.0, 0.10) << d << " m";
    EXPECT_LT(aliased, 4.0) << d << " m";
  }
}

}  // namespace
}  // namespace trackbed::render
