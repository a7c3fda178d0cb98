// The stereo camera as a device (robot/stereo_camera.h): its frames are the camera's
// stages composed by hand from their parts (renderer, exposures, image sensors,
// auto-exposure, blackout) to the byte; developing a pair elsewhere, later or out of
// order gives the same bytes; the auto-exposure brightens a dark scene frame by frame
// and holds still through a blackout; the pair is exposed the time offset after its
// stamp.
#include "trackbed/robot/stereo_camera.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/sensor_warp.h"
#include "trackbed/robot/as_built.h"
#include "trackbed/robot/tracked_vehicle.h"

namespace trackbed::robot {
namespace {

constexpr double kTimeOffsetS = 0.003;
const StereoCameraSeeds kSeeds{11, 12, 13};

// Textured plates 2.5 to 12 m ahead of a body looking along +x.
sim::World Scene() {
  return render::test::FlatWorld({render::test::Plate({2.5, 0.6, 1.0}, 0.5, 1.2, "brick"),
                                  render::test::Plate({4.0, -0.5, 0.8}, 0.8, 0.8, "wood"),
                                  render::test::Plate({12.0, 1.5, 2.0}, 3.0, 4.0, "bark")});
}

// A small camera (160 × 120) with harsh's lens, rolling shutter and sensor, a 4 ms
// exposure; `photometric` picks the electron model or the grey-level one.
StereoRigOptions Options(bool photometric, bool auto_exposure) {
  StereoRigOptions o;
  o.enabled = true;
  o.width_px = 160;
  o.height_px = 120;
  o.exposure_time_s = 0.004;
  o.noise_std = 2.0;
  o.exposure = 1.3;
  o.photometric.enabled = photometric;
  o.auto_exposure.enabled = auto_exposure;
  o.blackouts_s = {Eigen::Vector2d(0.25, 0.1)};  // the frame at 0.3 s
  return WithCameraEffectsResolved(o, Realism::kHarsh);
}

calibration::StereoCalibration AsBuilt(const StereoRigOptions& o) {
  return *DesignCalibration(TrackedVehicleOptions{}, o).stereo;
}

// The body at frame k of 10 a second: driving at 0.5 m/s while turning at 20°/s.
render::BodyMotion BodyAt(int k) {
  render::BodyMotion m;
  m.T_world_body.translation() = Eigen::Vector3d(0.05 * k, 0.0, 0.2);
  m.T_world_body.linear() = Eigen::AngleAxisd(0.035 * k, Eigen::Vector3d::UnitZ()).matrix();
  m.v_world = m.T_world_body.linear() * Eigen::Vector3d(0.5, 0.0, 0.0);
  m.omega_world = {0.0, 0.0, 0.35};
  return m;
}

// The camera's stages composed by hand from their parts, as the device documents them.
struct HandComposed {
  HandComposed(const StereoRigOptions& o, const sim::World& world,
               const render::SceneAppearance& appearance)
      : rig(o, AsBuilt(o)) {
    const int margin = 4;  // a lens, a rolling shutter, an exposure time
    const geometry::PinholeCamera render_left =
        render::Supersampled(render::RenderCameraFor(rig.intrinsics(), margin), o.supersampling);
    const geometry::PinholeCamera render_right = render::Supersampled(
        render::RenderCameraFor(rig.right_intrinsics(), margin), o.supersampling);
    const int w = std::max(render_left.width_px, render_right.width_px);
    const int h = std::max(render_left.height_px, render_right.height_px);
    renderer.emplace(world, appearance, std::vector<sim::OccluderSpec>{}, kSeeds.scene, w, h,
                     o.near_m, o.far_m);
    const double delay = *o.rolling_shutter.line_delay_s;
    exposures[0].emplace(rig.intrinsics(), render::GrownTo(render_left, w, h), o.exposure_samples,
                         delay);
    exposures[1].emplace(rig.right_intrinsics(), render::GrownTo(render_right, w, h),
                         o.exposure_samples, delay);
    if (o.auto_exposure.enabled) ae.emplace(o.auto_exposure, o.exposure_time_s);
    if (*o.photometric.enabled) {
      for (int camera = 0; camera < 2; ++camera) {
        sensors.emplace_back(o.photometric, o.width_px, o.height_px, kSeeds.pattern, camera);
      }
    }
  }

  // Frame `index` stamped `t_s`: both renders, the sensor, the blackout, the metering.
  void Take(std::int64_t index, double t_s, const render::BodyMotion& body) {
    const StereoRigOptions& o = rig.options();
    render::BodyMotion m = body;
    m.T_world_body = body.PoseAfter(kTimeOffsetS);
    const Eigen::Isometry3d T_left = m.T_world_body * rig.T_body_left();
    const Eigen::Isometry3d T_right = m.T_world_body * rig.T_body_right();
    const Eigen::Vector2d xy = 0.5 * (T_left.translation() + T_right.translation()).head<2>();
    exposure_time_s = ae ? ae->exposure_time_s() : o.exposure_time_s;
    gain = ae ? ae->gain() : 1.0;
    const double light = o.exposure * (ae ? exposure_time_s / o.exposure_time_s : 1.0);
    const bool clipped = renderer->pre_exposed();
    if (clipped) renderer->SetExposure(light);
    const double exposure = clipped ? 1.0 : light;
    exposures[0]->Render(*renderer, m, rig.T_body_left(), t_s + kTimeOffsetS, exposure_time_s,
                         &left, &xy);
    exposures[1]->Render(*renderer, m, rig.T_body_right(), t_s + kTimeOffsetS, exposure_time_s,
                         &right, &xy);
    const auto frame = static_cast<std::uint64_t>(index);
    if (!sensors.empty()) {
      sensors[0].Apply(exposure, kSeeds.noise, frame, &left, gain, clipped);
      sensors[1].Apply(exposure, kSeeds.noise, frame, &right, gain, clipped);
    } else {
      ApplySensorModel(exposure * gain, o.noise_std, kSeeds.noise, frame, 0, &left);
      ApplySensorModel(exposure * gain, o.noise_std, kSeeds.noise, frame, 1, &right);
    }
    const bool blackout = o.InBlackout(t_s);
    if (blackout) {
      std::fill(left.pixels.begin(), left.pixels.end(), 0);
      std::fill(right.pixels.begin(), right.pixels.end(), 0);
    }
    if (ae && !blackout) ae->Update(ae->Meter(left), 1.0 / o.rate_hz);
  }

  StereoRig rig;
  std::optional<render::Renderer> renderer;
  std::optional<render::CameraExposure> exposures[2];
  std::vector<ImageSensor> sensors;
  std::optional<AutoExposure> ae;
  GrayImage left, right;
  double exposure_time_s = 0.0, gain = 1.0;
};

double Mean(const GrayImage& image) {
  return std::accumulate(image.pixels.begin(), image.pixels.end(), 0.0) /
         static_cast<double>(image.pixels.size());
}

TEST(StereoCameraTest, TheFramesAreTheStagesComposedByHand) {
  const sim::World world = Scene();
  render::SceneAppearance lit = render::test::AmbientOnly();
  lit.sky_gray = 0.6;
  lit.lighting = render::SceneLighting{};  // pre-exposed renders
  struct Case {
    bool photometric, auto_exposure;
    render::SceneAppearance appearance;
  };
  for (const Case& c : {Case{false, false, render::test::AmbientOnly()}, Case{true, false, lit},
                        Case{true, true, lit}, Case{false, true, render::test::AmbientOnly()}}) {
    const StereoRigOptions o = Options(c.photometric, c.auto_exposure);
    StereoCamera camera(o, AsBuilt(o), kTimeOffsetS, world, c.appearance, {}, kSeeds);
    HandComposed hand(o, world, c.appearance);
    for (int k = 0; k < 6; ++k) {
      SCOPED_TRACE(testing::Message() << "photometric " << c.photometric << ", auto-exposure "
                                      << c.auto_exposure << ", frame " << k);
      const StereoCapture s = camera.Capture(0.1 * k, BodyAt(k));
      hand.Take(k, 0.1 * k, BodyAt(k));
      EXPECT_EQ(s.index, k);
      EXPECT_EQ(s.blackout, k == 3);
      EXPECT_EQ(s.exposure_time_s, hand.exposure_time_s);
      EXPECT_EQ(s.gain, hand.gain);
      ASSERT_EQ(s.left->pixels, hand.left.pixels);
      ASSERT_EQ(s.right->pixels, hand.right.pixels);
      if (k == 0) {
        EXPECT_GT(Mean(*s.left), 5.0);  // the scene is seen
      }
    }
    EXPECT_EQ(camera.frames(), 6);
  }
}

TEST(StereoCameraTest, DevelopingElsewhereLaterOrOutOfOrderGivesTheSameBytes) {
  const sim::World world = Scene();
  const render::SceneAppearance appearance = render::test::AmbientOnly();
  const StereoRigOptions o = Options(true, false);
  StereoCamera at_once(o, AsBuilt(o), kTimeOffsetS, world, appearance, {}, kSeeds);
  StereoCamera deferred(o, AsBuilt(o), kTimeOffsetS, world, appearance, {}, kSeeds);
  // Each frame into its own buffers, as the closed loop hands them to its worker.
  std::vector<GrayImage> lefts(4), rights(4);
  std::vector<StereoCapture> exposed;
  for (int k = 0; k < 4; ++k) {
    exposed.push_back(deferred.Expose(0.1 * k, BodyAt(k), &lefts[k], &rights[k]));
    EXPECT_EQ(exposed.back().left, &lefts[k]);
  }
  for (int k = 3; k >= 0; --k) deferred.Develop(exposed[k]);
  for (int k = 0; k < 4; ++k) {
    const StereoCapture s = at_once.Capture(0.1 * k, BodyAt(k));
    EXPECT_EQ(s.left->pixels, lefts[k].pixels) << "frame " << k;
    EXPECT_EQ(s.right->pixels, rights[k].pixels) << "frame " << k;
    const bool black = std::all_of(lefts[k].pixels.begin(), lefts[k].pixels.end(),
                                   [](std::uint8_t p) { return p == 0; });
    EXPECT_EQ(black, k == 3) << "frame " << k;  // the blackout, wherever developed
  }
}

// A dark scene: the auto-exposure lengthens the exposure frame by frame and the image
// brightens to the target; a blackout frame meters nothing, so the frame after
// it keeps its settings.
TEST(StereoCameraTest, TheAutoExposureBrightensADarkSceneAndHoldsStillInABlackout) {
  const sim::World world = Scene();
  render::SceneAppearance dark = render::test::AmbientOnly();
  dark.ambient = 0.15;
  dark.sky_gray = 0.1;
  StereoRigOptions o = Options(true, true);
  o.auto_exposure.max_exposure_s = 0.05;
  o.blackouts_s = {Eigen::Vector2d(1.05, 0.1)};  // the frame at 1.1 s
  StereoCamera camera(o, AsBuilt(o), 0.0, world, dark, {}, kSeeds);
  std::vector<StereoCapture> frames;
  std::vector<double> means;
  for (int k = 0; k < 14; ++k) {
    frames.push_back(camera.Capture(0.1 * k, BodyAt(0)));
    means.push_back(Mean(*frames.back().left));
    std::printf("frame %2d: exposure %.2f ms, gain %.2f, mean grey %.1f\n", k,
                1e3 * frames.back().exposure_time_s, frames.back().gain, means.back());
  }
  EXPECT_EQ(frames[0].exposure_time_s, o.exposure_time_s);
  EXPECT_EQ(frames[0].gain, 1.0);
  for (int k = 1; k <= 10; ++k) {
    EXPECT_GT(frames[k].exposure_time_s, frames[k - 1].exposure_time_s) << "frame " << k;
    EXPECT_GT(means[k], means[k - 1]) << "frame " << k;
  }
  EXPECT_EQ(means[11], 0.0);  // the blackout
  EXPECT_EQ(frames[12].exposure_time_s, frames[11].exposure_time_s);
  EXPECT_EQ(frames[12].gain, frames[11].gain);
  EXPECT_GT(frames[13].exposure_time_s * frames[13].gain,
            frames[12].exposure_time_s * frames[12].gain);
  EXPECT_NEAR(means[13], o.auto_exposure.target_grey, 3.0);
}

TEST(StereoCameraTest, ThePairIsExposedTheTimeOffsetAfterItsStamp) {
  const sim::World world = Scene();
  const StereoRigOptions o = Options(false, false);
  for (const double offset : {0.0, 0.02}) {
    StereoCamera camera(o, AsBuilt(o), offset, world, render::test::AmbientOnly(), {}, kSeeds);
    const render::BodyMotion body = BodyAt(2);
    const StereoCapture s = camera.Capture(0.2, body);
    const Eigen::Isometry3d T_body = body.PoseAfter(offset);
    EXPECT_TRUE(s.T_world_left.isApprox(T_body * camera.rig().T_body_left(), 1e-12));
    EXPECT_TRUE(s.T_world_right.isApprox(T_body * camera.rig().T_body_right(), 1e-12));
    EXPECT_EQ(s.t_s, 0.2);
  }
}

}  // namespace
}  // namespace trackbed::robot
