// Curved objects' outlines as a camera samples them: upright posts against a black sky,
// seen by the robot's camera (f 381 px) level at their mid-height, against the same view
// drawn 4 × 4 times as finely and averaged over each pixel. A pixel the outline crosses
// takes the fraction of it the post covers (renderer's outline pass, surface_program.h),
// not all or nothing: on the pixels the reference shows partly covered, the difference
// stays under a tenth of the post's grey level RMS (8.5 %; without the outline pass
// 45 %), and the posts keep their width within 2 % (0.05 %; without it 8 % wider). The
// depth image holds the post's depth where the post covers most of the pixel, the
// sky's where it covers little.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/sensor_warp.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::render {
namespace {

constexpr int kFactor = 4;        // the reference's render pixels per pixel, each way
constexpr double kHeightM = 0.5;  // the camera above the ground
constexpr int kPosts = 6;

// Posts 4–6.5 m ahead, spread across the view at offsets that put their outlines at
// different fractions of a pixel.
std::vector<sim::StaticObject> Posts() {
  std::vector<sim::StaticObject> out;
  for (int k = 0; k < kPosts; ++k) {
    sim::StaticObject o;
    o.shape = sim::StaticObject::Shape::kCylinder;
    o.kind = "post";
    o.appearance = "plain_paint";
    o.center_m = {4.0 + 0.5 * k, -2.0 + 0.8 * k + 0.037 * k};
    o.base_z_m = 0.0;
    o.radius_m = 0.06 + 0.01 * k;
    o.height_m = 1.2;
    out.push_back(o);
  }
  return out;
}

// The camera at (0, 0, kHeightM) looking level along +x (OpenCV axes).
Eigen::Isometry3d CameraPose() {
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(0, -1, 0);
  R.col(1) = Eigen::Vector3d(0, 0, -1);
  R.col(2) = Eigen::Vector3d(1, 0, 0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = Eigen::Vector3d(0, 0, kHeightM);
  return T;
}

TEST(OutlineCoverageTest, PixelsOnAPostsOutlineTakeTheFractionItCovers) {
  const sim::World world = test::FlatWorld(Posts(), {-2, -8, 20, 8});
  const geometry::PinholeCamera K = robot::StereoRig(robot::StereoRigOptions{}).intrinsics();
  const geometry::PinholeCamera fine = Supersampled(K, kFactor);
  Renderer coarse(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0);
  Renderer sharp(world, test::AmbientOnly(), {}, 1, fine.width_px, fine.height_px, 0.05, 120.0);
  GrayImage image, big;
  coarse.Render(K, CameraPose(), 0.0, &image, nullptr);
  sharp.Render(fine, CameraPose(), 0.0, &big, nullptr);

  // Rows from 0.1 to 0.6 m above the camera at the nearest post: against the sky.
  const int top = static_cast<int>(K.cy - K.fy * 0.6 / 4.0);
  const int bottom = static_cast<int>(K.cy - K.fy * 0.1 / 4.0);
  double post_grey = 0.0;
  for (int x = 0; x < K.width_px; ++x) {
    post_grey = std::max(post_grey, static_cast<double>(image.pixels[top * K.width_px + x]));
  }
  ASSERT_GT(post_grey, 50.0);
  double sum_sq = 0.0, image_sum = 0.0, reference_sum = 0.0;
  int edge_pixels = 0;
  for (int y = top; y <= bottom; ++y) {
    for (int x = 0; x < K.width_px; ++x) {
      int sum = 0;
      for (int j = 0; j < kFactor; ++j) {
        for (int i = 0; i < kFactor; ++i) {
          sum +=
              big.pixels[static_cast<std::size_t>((kFactor * y + j) * big.width + kFactor * x + i)];
        }
      }
      const double reference = static_cast<double>(sum) / (kFactor * kFactor);
      const double drawn = image.pixels[static_cast<std::size_t>(y * K.width_px + x)];
      image_sum += drawn;
      reference_sum += reference;
      if (reference > 0.1 * post_grey && reference < 0.9 * post_grey) {
        sum_sq += (drawn - reference) * (drawn - reference);
        ++edge_pixels;
      }
    }
  }
  const double rms = std::sqrt(sum_sq / std::max(edge_pixels, 1));
  std::printf("post grey %.0f, %d partly covered pixels, RMS difference %.2f, width %+.2f %%\n",
              post_grey, edge_pixels, rms, 100.0 * (image_sum / reference_sum - 1.0));
  EXPECT_GT(edge_pixels, kPosts * (bottom - top));  // at least one a post and row
  EXPECT_LT(rms, 0.1 * post_grey);
  EXPECT_NEAR(image_sum / reference_sum, 1.0, 0.02);
}

TEST(OutlineCoverageTest, APixelTakesTheDepthOfWhatCoversMostOfIt) {
  const sim::World world = test::FlatWorld(Posts(), {-2, -8, 20, 8});
  const geometry::PinholeCamera K = robot::StereoRig(robot::StereoRigOptions{}).intrinsics();
  const geometry::PinholeCamera fine = Supersampled(K, kFactor);
  Renderer coarse(world, test::AmbientOnly(), {}, 1, K.width_px, K.height_px, 0.05, 120.0);
  Renderer sharp(world, test::AmbientOnly(), {}, 1, fine.width_px, fine.height_px, 0.05, 120.0);
  GrayImage image, big;
  DepthImage depth, big_depth;
  coarse.Render(K, CameraPose(), 0.0, &image, &depth);
  sharp.Render(fine, CameraPose(), 0.0, &big, &big_depth);

  // The rows against the sky, as above; each pixel's covered fraction from the
  // reference's 16 samples (a post's depth is finite, the sky's infinite).
  const int top = static_cast<int>(K.cy - K.fy * 0.6 / 4.0);
  const int bottom = static_cast<int>(K.cy - K.fy * 0.1 / 4.0);
  int mostly = 0, mostly_post = 0, little = 0, little_sky = 0;
  for (int y = top; y <= bottom; ++y) {
    for (int x = 0; x < K.width_px; ++x) {
      int covered = 0;
      for (int j = 0; j < kFactor; ++j) {
        for (int i = 0; i < kFactor; ++i) {
          covered += std::isfinite(big_depth.at(kFactor * x + i, kFactor * y + j));
        }
      }
      const bool post = std::isfinite(depth.at(x, y));
      if (covered >= 11 && covered < kFactor * kFactor) {
        ++mostly;
        mostly_post += post;
      } else if (covered > 0 && covered <= 5) {
        ++little;
        little_sky += !post;
      }
    }
  }
  std::printf("mostly covered: %d of %d with the post's depth; little: %d of %d the sky's\n",
              mostly_post, mostly, little_sky, little);
  EXPECT_GT(mostly, kPosts * (bottom - top) / 4);  // a side of a post every other row
  EXPECT_GT(little, kPosts * (bottom - top) / 4);
  EXPECT_EQ(mostly_post, mostly);
  EXPECT_EQ(little_sky, little);
}

}  // namespace
}  // namespace trackbed::render
