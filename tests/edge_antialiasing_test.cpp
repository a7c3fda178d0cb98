// Antialiased edges of drawn geometry (render/edge_antialiasing.h): plates against a
// black sky seen by the robot's camera (f 381 px) level at 0.5 m, their upright edges at
// known sub-pixel positions. With four samples a pixel, a pixel an edge crosses takes
// the plate's grey times the fraction of the pixel the plate covers, to the eighth of a
// pixel the samples' four columns resolve; with one sample it is all or nothing. Seen
// with the camera rolled 10, 20, 30 and 45 degrees, the slanted edges' pixels follow a
// 4 x 4 supersampled reference: RMS 0.09-0.16 of the plate's grey with four samples,
// 0.31-0.33 with one. The depth of a pixel is one surface's, sample 0's, never a mean
// across the edge; reruns give the same bytes.
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/sensor_warp.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::render {
namespace {

constexpr double kDistanceM = 4.0;  // the plates' front faces ahead of the camera
constexpr double kEyeZ = 0.5;       // the camera above the floor
constexpr double kBottomZ = 0.7, kTopZ = 1.3;
constexpr int kPlates = 5;

geometry::PinholeCamera Camera() {
  return robot::StereoRig(robot::StereoRigOptions{}).intrinsics();
}

// The image column u (pixel centres at integers) of world y at depth x.
double Column(const geometry::PinholeCamera& K, double y, double x) { return K.cx - K.fx * y / x; }

// Plates whose left edges fall at 0.1, 0.3, 0.5, 0.7, 0.9 of a pixel past a pixel's
// left side and whose right edges at 0.2, 0.4, ... past theirs: each 40.5 px wide.
std::vector<sim::StaticObject> Plates(const geometry::PinholeCamera& K, std::vector<double>* left_u,
                                      std::vector<double>* right_u) {
  std::vector<sim::StaticObject> out;
  for (int k = 0; k < kPlates; ++k) {
    const double left = std::floor(K.cx) - 250.0 + 100.0 * k - 0.5 + 0.1 + 0.2 * k;
    const double right = left + 40.5 + 0.1;
    const double y_left = (K.cx - left) * kDistanceM / K.fx;
    const double y_right = (K.cx - right) * kDistanceM / K.fx;
    out.push_back(test::Plate({kDistanceM, 0.5 * (y_left + y_right), 0.5 * (kBottomZ + kTopZ)},
                              y_left - y_right, kTopZ - kBottomZ, "plain_paint"));
    // The outline is the nearer of the front and back corners' (1 mm deeper).
    left_u->push_back(
        std::min(Column(K, y_left, kDistanceM), Column(K, y_left, kDistanceM + 1e-3)));
    right_u->push_back(
        std::max(Column(K, y_right, kDistanceM), Column(K, y_right, kDistanceM + 1e-3)));
  }
  return out;
}

Eigen::Isometry3d LevelCamera(double roll_rad = 0.0) {
  Eigen::Isometry3d T = test::Looking({0, 0, kEyeZ}, {1, 0, 0});
  T.linear() =
      T.linear() * Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

struct Rows {
  int top, bottom;
};
Rows PlateRows(const geometry::PinholeCamera& K) {
  return {static_cast<int>(std::ceil(K.cy - K.fy * (kTopZ - kEyeZ) / kDistanceM)) + 2,
          static_cast<int>(std::floor(K.cy - K.fy * (kBottomZ - kEyeZ) / kDistanceM)) - 2};
}

double Grey(const GrayImage& im, int u, int v) {
  return im.pixels[static_cast<std::size_t>(v) * im.width + u];
}

// The largest |grey - fraction x the plate's grey| over the edge pixels of every row,
// as a fraction of the plate's grey (the grey two pixels inside the edge).
double WorstEdgeError(const GrayImage& im, const std::vector<double>& left_u,
                      const std::vector<double>& right_u, const Rows& rows) {
  double worst = 0.0;
  for (int v = rows.top; v <= rows.bottom; ++v) {
    for (int k = 0; k < kPlates; ++k) {
      const int l = static_cast<int>(std::lround(left_u[k]));
      const int r = static_cast<int>(std::lround(right_u[k]));
      const double inside_l = Grey(im, l + 2, v), inside_r = Grey(im, r - 2, v);
      EXPECT_GT(inside_l, 50.0);
      const double fraction_l = l + 0.5 - left_u[k], fraction_r = right_u[k] - (r - 0.5);
      worst = std::max(worst, std::abs(Grey(im, l, v) - fraction_l * inside_l) / inside_l);
      worst = std::max(worst, std::abs(Grey(im, r, v) - fraction_r * inside_r) / inside_r);
      EXPECT_EQ(Grey(im, l - 1, v), 0.0);  // the sky's, beside the edge pixel
      EXPECT_EQ(Grey(im, r + 1, v), 0.0);
    }
  }
  return worst;
}

TEST(EdgeAntialiasingTest, AnEdgePixelTakesTheFractionThePlateCovers) {
  const geometry::PinholeCamera K = Camera();
  std::vector<double> left_u, right_u;
  const sim::World world = test::FlatWorld(Plates(K, &left_u, &right_u), {-2, -8, 20, 8});
  Renderer one(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0);
  Renderer four(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0, 4);
  GrayImage a, b;
  one.Render(K, LevelCamera(), 0.0, &a, nullptr);
  four.Render(K, LevelCamera(), 0.0, &b, nullptr);
  const Rows rows = PlateRows(K);
  const double worst_one = WorstEdgeError(a, left_u, right_u, rows);
  const double worst_four = WorstEdgeError(b, left_u, right_u, rows);
  std::printf("worst edge pixel error, of the plate's grey: one sample %.3f, four %.3f\n",
              worst_one, worst_four);
  // Four columns of samples place an upright edge to an eighth of a pixel (plus the
  // paint's texture, under 1.5 grey levels, and rounding).
  EXPECT_LT(worst_four, 0.125 + 0.02);
  EXPECT_GT(worst_one, 0.3);  // the fractions 0.1 ... 0.9 shown as 0 or 1
}

TEST(EdgeAntialiasingTest, SlantedEdgesFollowASupersampledReference) {
  const geometry::PinholeCamera K = Camera();
  const geometry::PinholeCamera fine = Supersampled(K, 4);
  std::vector<double> left_u, right_u;
  const sim::World world = test::FlatWorld(Plates(K, &left_u, &right_u), {-2, -8, 20, 8});
  Renderer one_r(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0);
  Renderer four_r(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0, 4);
  Renderer big_r(world, test::AmbientOnly(), {}, 1, fine.width_px, fine.height_px, 0.05, 120.0);
  for (double roll_deg : {10.0, 20.0, 30.0, 45.0}) {
    const Eigen::Isometry3d T = LevelCamera(roll_deg * M_PI / 180.0);
    GrayImage one, four, big;
    DepthImage big_depth;
    one_r.Render(K, T, 0.0, &one, nullptr);
    four_r.Render(K, T, 0.0, &four, nullptr);
    big_r.Render(fine, T, 0.0, &big, &big_depth);
    // The plates' grey, and the pixels the reference shows as plate and sky alone (the
    // floor is seen too with the camera rolled), partly covered.
    double plate = 0.0, sq_one = 0.0, sq_four = 0.0;
    for (std::size_t k = 0; k < big.pixels.size(); ++k) {
      if (std::abs(big_depth.depth_m[k] - kDistanceM) < 0.01)
        plate = std::max(plate, static_cast<double>(big.pixels[k]));
    }
    ASSERT_GT(plate, 50.0);
    int edge = 0;
    for (int v = 0; v < K.height_px; ++v) {
      for (int u = 0; u < K.width_px; ++u) {
        double sum = 0.0;
        bool floor = false;
        for (int j = 0; j < 4; ++j) {
          for (int i = 0; i < 4; ++i) {
            sum += Grey(big, 4 * u + i, 4 * v + j);
            const double z =
                big_depth.depth_m[static_cast<std::size_t>(4 * v + j) * big.width + 4 * u + i];
            floor = floor || (std::isfinite(z) && std::abs(z - kDistanceM) >= 0.01);
          }
        }
        const double reference = sum / 16.0;
        if (floor || reference < 0.1 * plate || reference > 0.9 * plate) continue;
        ++edge;
        sq_one += std::pow(Grey(one, u, v) - reference, 2);
        sq_four += std::pow(Grey(four, u, v) - reference, 2);
      }
    }
    const double rms_one = std::sqrt(sq_one / edge) / plate;
    const double rms_four = std::sqrt(sq_four / edge) / plate;
    std::printf(
        "roll %2.0f deg, %d edge pixels; RMS against the reference, of the plate's "
        "grey: one sample %.3f, four %.3f\n",
        roll_deg, edge, rms_one, rms_four);
    EXPECT_GT(edge, kPlates * 100);
    EXPECT_GT(rms_one, 0.2);  // a step: 1/sqrt(12) = 0.29 of the contrast
    // Along an edge's normal the four samples fall at four distinct offsets at most
    // angles; at worst they pair up into two, a staircase of half the step: 0.29 / 2,
    // plus the reference's sixteenths (0.018).
    EXPECT_LT(rms_four, 0.145 + 0.025);
  }
}

TEST(EdgeAntialiasingTest, ADepthIsOneSurfacesAndRerunsAreTheSameBytes) {
  const geometry::PinholeCamera K = Camera();
  std::vector<double> left_u, right_u;
  const sim::World world = test::FlatWorld(Plates(K, &left_u, &right_u), {-2, -8, 20, 8});
  Renderer first(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0, 4);
  Renderer second(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0, 4);
  GrayImage a, b, c;
  DepthImage da, db, dc;
  first.Render(K, LevelCamera(), 0.0, &a, &da);
  second.Render(K, LevelCamera(0.35), 0.0, &b, &db);  // another frame between
  second.Render(K, LevelCamera(), 0.0, &b, &db);
  first.Render(K, LevelCamera(), 0.0, &c, &dc);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(a.pixels, c.pixels);
  EXPECT_EQ(da.depth_m, db.depth_m);
  EXPECT_EQ(da.depth_m, dc.depth_m);

  // Along the plates' rows every depth is the plate's or the sky's; at an edge pixel the
  // plate's exactly where it covers sample 0, at 0.375 of the pixel from its left side.
  const Rows rows = PlateRows(K);
  for (int v = rows.top; v <= rows.bottom; ++v) {
    for (int u = 0; u < K.width_px; ++u) {
      const double z = da.depth_m[static_cast<std::size_t>(v) * K.width_px + u];
      ASSERT_TRUE(std::isinf(z) || std::abs(z - kDistanceM) < 1e-3) << u << ", " << v << ": " << z;
    }
    for (int k = 0; k < kPlates; ++k) {
      const int l = static_cast<int>(std::lround(left_u[k]));
      const int r = static_cast<int>(std::lround(right_u[k]));
      const double sample0_l = l - 0.5 + 0.375, sample0_r = r - 0.5 + 0.375;
      EXPECT_EQ(std::isinf(da.depth_m[static_cast<std::size_t>(v) * K.width_px + l]),
                sample0_l < left_u[k])
          << "plate " << k;
      EXPECT_EQ(std::isinf(da.depth_m[static_cast<std::size_t>(v) * K.width_px + r]),
                sample0_r > right_u[k])
          << "plate " << k;
    }
  }
}

TEST(EdgeAntialiasingTest, OtherSampleCountsAreRefused) {
  const sim::World world = test::FlatWorld({});
  for (int samples : {0, 2, 3, 8}) {
    EXPECT_THROW(Renderer(world, test::AmbientOnly(), {}, 1, 64, 48, 0.05, 120.0, samples),
                 std::invalid_argument);
  }
}

}  // namespace
}  // namespace trackbed::render
