// The sky: every sky pixel shows the CIE clear sky's luminance of its own view direction
// (the sun's brightest point where the pinhole projects the sun), the sky does not
// move when the camera translates, clouds come from the seed, reruns give the same
// bytes, and the flat sky is unchanged.
#include "trackbed/render/sky.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/renderer.h"
#include "trackbed/render/scene_lighting.h"

namespace trackbed::render {
namespace {

constexpr double kFarM = 60.0;

SceneAppearance Sky(SkyLook look, double gray = 0.12) {
  SceneAppearance a = test::AmbientOnly();
  a.sky = look;
  a.sky_gray = gray;  // dim enough that the sun's aureole does not clip
  a.sun_azimuth_deg = 20.0;
  a.sun_elevation_deg = 25.0;
  return a;
}

// A camera at `eye` looking along azimuth `yaw_deg`, pitched up by `pitch_deg`.
Eigen::Isometry3d Camera(const Eigen::Vector3d& eye, double yaw_deg, double pitch_deg) {
  const double yaw = yaw_deg * M_PI / 180.0, pitch = pitch_deg * M_PI / 180.0;
  return test::Looking(eye, Eigen::Vector3d(std::cos(yaw) * std::cos(pitch),
                                            std::sin(yaw) * std::cos(pitch), std::sin(pitch)));
}

struct View {
  GrayImage gray;
  DepthImage depth;
};

View Draw(Renderer& r, const geometry::PinholeCamera& K, const Eigen::Isometry3d& T) {
  View v;
  r.Render(K, T, 0.0, &v.gray, &v.depth);
  return v;
}

bool IsSky(const View& v, int u, int row) { return v.depth.at(u, row) >= 0.999 * kFarM; }

TEST(SkyTest, EverySkyPixelShowsTheClearSkyOfItsViewDirection) {
  const sim::World world = test::FlatWorld({});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(320, 240, 80.0 * M_PI / 180.0);
  const SceneAppearance a = Sky(SkyLook::kClear);
  Renderer r(world, a, {}, 4, 320, 240, 0.05, kFarM);
  const Eigen::Vector3d sun = SunDirection(a.sun_azimuth_deg, a.sun_elevation_deg);
  for (const Eigen::Isometry3d& T :
       {Camera({0, 0, 1.5}, 10.0, 5.0), Camera({0, 0, 1.5}, 40.0, 30.0),
        Camera({3, -2, 1.0}, 200.0, 20.0)}) {
    const View v = Draw(r, K, T);
    int sky = 0, off = 0, brightest_u = -1, brightest_v = -1, brightest = -1;
    for (int row = 0; row < K.height_px; ++row) {
      for (int u = 0; u < K.width_px; ++u) {
        if (!IsSky(v, u, row)) continue;
        ++sky;
        const Eigen::Vector3d dir =
            (T.linear() * Eigen::Vector3d((u - K.cx) / K.fx, (row - K.cy) / K.fy, 1.0))
                .normalized();
        const double expected =
            std::round(255.0 * std::min(a.sky_gray * ClearSkyLuminance(dir, sun), 1.0));
        off += std::abs(v.gray.at(u, row) - expected) > 1.0;
        if (v.gray.at(u, row) > brightest) {
          brightest = v.gray.at(u, row);
          brightest_u = u;
          brightest_v = row;
        }
      }
    }
    EXPECT_GT(sky, 5000);
    EXPECT_EQ(off, 0);
    const Eigen::Vector3d sun_camera = T.linear().transpose() * sun;
    if (sun_camera.z() > 0.0) {  // the sun in view: its brightest pixel where it projects
      const Eigen::Vector2d p = K.Project(sun_camera);
      std::printf("sun at (%.2f, %.2f) px, brightest sky pixel (%d, %d)\n", p.x(), p.y(),
                  brightest_u, brightest_v);
      EXPECT_LE(std::abs(brightest_u - p.x()), 1.0);
      EXPECT_LE(std::abs(brightest_v - p.y()), 1.0);
    }
  }
}

TEST(SkyTest, TheSkyMovesWithRotationNotTranslation) {
  const sim::World world = test::FlatWorld({});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(320, 240, 80.0 * M_PI / 180.0);
  Renderer r(world, Sky(SkyLook::kCloudy, 0.6), {}, 4, 320, 240, 0.05, kFarM);
  const View a = Draw(r, K, Camera({0, 0, 1.5}, 30.0, 25.0));
  const View b = Draw(r, K, Camera({4, 3, 1.9}, 30.0, 25.0));
  const View turned = Draw(r, K, Camera({0, 0, 1.5}, 35.0, 25.0));
  int both = 0, same = 0, moved = 0;
  for (int row = 0; row < K.height_px; ++row) {
    for (int u = 0; u < K.width_px; ++u) {
      if (!IsSky(a, u, row) || !IsSky(b, u, row) || !IsSky(turned, u, row)) continue;
      ++both;
      same += a.gray.at(u, row) == b.gray.at(u, row);
      moved += a.gray.at(u, row) != turned.gray.at(u, row);
    }
  }
  EXPECT_GT(both, 10000);
  EXPECT_EQ(same, both);       // 5 m away, the same sky
  EXPECT_GT(moved, both / 4);  // 5 degrees round, the clouds moved
}

TEST(SkyTest, CloudsComeFromTheSeedAndRerunsGiveTheSameBytes) {
  const sim::World world = test::FlatWorld({});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(320, 240, 80.0 * M_PI / 180.0);
  const Eigen::Isometry3d T = Camera({0, 0, 1.5}, 100.0, 35.0);
  GrayImage first, second, other, clear;
  Renderer(world, Sky(SkyLook::kCloudy, 0.6), {}, 4, 320, 240, 0.05, kFarM)
      .Render(K, T, 0.0, &first, nullptr);
  Renderer(world, Sky(SkyLook::kCloudy, 0.6), {}, 4, 320, 240, 0.05, kFarM)
      .Render(K, T, 0.0, &second, nullptr);
  Renderer(world, Sky(SkyLook::kCloudy, 0.6), {}, 5, 320, 240, 0.05, kFarM)
      .Render(K, T, 0.0, &other, nullptr);
  Renderer(world, Sky(SkyLook::kClear, 0.6), {}, 4, 320, 240, 0.05, kFarM)
      .Render(K, T, 0.0, &clear, nullptr);
  EXPECT_EQ(first.pixels, second.pixels);
  EXPECT_NE(first.pixels, other.pixels);
  int clouded = 0;
  for (std::size_t i = 0; i < first.pixels.size(); ++i) {
    clouded += std::abs(first.pixels[i] - clear.pixels[i]) > 8;
  }
  // Clouds over a good part of the upper view (the lower part is ground).
  EXPECT_GT(clouded, static_cast<int>(first.pixels.size()) / 10);
}

TEST(SkyTest, TheFlatSkyIsTheSkyGrey) {
  const sim::World world = test::FlatWorld({});
  const geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(160, 120, 80.0 * M_PI / 180.0);
  Renderer r(world, Sky(SkyLook::kFlat, 0.5), {}, 4, 160, 120, 0.05, kFarM);
  const View v = Draw(r, K, Camera({0, 0, 1.5}, 0.0, 40.0));
  EXPECT_EQ(v.gray.at(80, 2), 128);  // 0.5 of 255, rounded
}

}  // namespace
}  // namespace trackbed::render
