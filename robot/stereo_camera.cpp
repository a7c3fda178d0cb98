// The stereo camera as a device (see stereo_camera.h).
#include "trackbed/robot/stereo_camera.h"

#include <algorithm>
#include <utility>

#include "trackbed/render/sensor_warp.h"

namespace trackbed::robot {
namespace {

// The body's motion `dt_s` later at constant velocity (dt small: a camera's time offset).
render::BodyMotion Advanced(const render::BodyMotion& m, double dt_s) {
  if (dt_s == 0.0) return m;
  render::BodyMotion out = m;
  out.T_world_body = m.PoseAfter(dt_s);
  return out;
}

}  // namespace

// One renderer for both cameras, sized for the wider of their renders through the lens,
// and each camera's exposure.
StereoCamera::StereoCamera(const StereoRigOptions& options,
                           const calibration::StereoCalibration& as_built, double time_offset_s,
                           const sim::World& world, const render::SceneAppearance& appearance,
                           std::vector<sim::OccluderSpec> occluders, const StereoCameraSeeds& seeds)
    : rig_(options, as_built), time_offset_s_(time_offset_s), noise_seed_(seeds.noise) {
  const StereoRigOptions& o = rig_.options();
  // Four pixels of margin: what a rolling shutter or blur warp may reach past the edge;
  // the render drawn `supersampling` times as finely.
  const int margin =
      o.distortion->is_zero() && *o.rolling_shutter.line_delay_s == 0 && o.exposure_time_s == 0 ? 0
                                                                                                : 4;
  const geometry::PinholeCamera left =
      render::Supersampled(render::RenderCameraFor(rig_.intrinsics(), margin), o.supersampling);
  const geometry::PinholeCamera right = render::Supersampled(
      render::RenderCameraFor(rig_.right_intrinsics(), margin), o.supersampling);
  const int w = std::max(left.width_px, right.width_px);
  const int h = std::max(left.height_px, right.height_px);
  renderer_ =
      std::make_unique<render::Renderer>(world, appearance, std::move(occluders), seeds.scene, w, h,
                                         o.near_m, o.far_m, o.edge_antialiasing_samples);
  const double line_delay = *o.rolling_shutter.line_delay_s;
  exposures_[0] = std::make_unique<render::CameraExposure>(
      rig_.intrinsics(), render::GrownTo(left, w, h), o.exposure_samples, line_delay);
  exposures_[1] = std::make_unique<render::CameraExposure>(
      rig_.right_intrinsics(), render::GrownTo(right, w, h), o.exposure_samples, line_delay);
  if (o.auto_exposure.enabled) auto_exposure_.emplace(o.auto_exposure, o.exposure_time_s);
  if (*o.photometric.enabled) {
    for (int camera = 0; camera < 2; ++camera) {
      image_sensors_.emplace_back(o.photometric, o.width_px, o.height_px, seeds.pattern, camera);
    }
  }
}

StereoCamera::~StereoCamera() = default;

void StereoCamera::SetBodyShape(std::vector<render::ShadowBox> boxes_body) {
  renderer_->SetRobotShape(std::move(boxes_body));
}

void StereoCamera::SetTrackMarks(const sim::TrackMarks* marks) { renderer_->SetTrackMarks(marks); }

StereoCapture StereoCamera::Capture(double t_s, const render::BodyMotion& body, GrayImage* left,
                                    GrayImage* right) {
  const StereoCapture capture = Expose(t_s, body, left, right);
  Finish(capture);
  return capture;
}

StereoCapture StereoCamera::Expose(double t_s, const render::BodyMotion& body, GrayImage* left,
                                   GrayImage* right) {
  const StereoRigOptions& o = rig_.options();
  StereoCapture c;
  c.index = frames_++;
  c.t_s = t_s;
  c.left = left ? left : &left_;
  c.right = right ? right : &right_;
  // The pair stamped now was exposed `time_offset_s` later on the IMU's clock.
  const render::BodyMotion motion = Advanced(body, time_offset_s_);
  c.T_world_left = motion.T_world_body * rig_.T_body_left();
  c.T_world_right = motion.T_world_body * rig_.T_body_right();
  // Both cameras see the terrain at the detail of the rig's centre.
  const Eigen::Vector2d rig_xy =
      0.5 * (c.T_world_left.translation() + c.T_world_right.translation()).head<2>();
  // Each image is exposed around the frame's time (an instant by default), for the time
  // the auto-exposure chose if it is on.
  c.exposure_time_s = auto_exposure_ ? auto_exposure_->exposure_time_s() : o.exposure_time_s;
  c.gain = auto_exposure_ ? auto_exposure_->gain() : 1.0;
  // The render shows the scene at `exposure_time_s`; the light scales with the time.
  // With scene lighting the renderer applies it before its output clips (a zone
  // brighter than the exposure holds saturates), else the sensor model does.
  const double light = o.exposure * (auto_exposure_ ? c.exposure_time_s / o.exposure_time_s : 1.0);
  c.clipped_render = renderer_->pre_exposed();
  if (c.clipped_render) renderer_->SetExposure(light);
  c.sensor_exposure = c.clipped_render ? 1.0 : light;
  renderer_->SetRobotPose(motion.T_world_body);  // for its shadow
  exposures_[0]->Render(*renderer_, motion, rig_.T_body_left(), t_s + time_offset_s_,
                        c.exposure_time_s, c.left, &rig_xy);
  exposures_[1]->Render(*renderer_, motion, rig_.T_body_right(), t_s + time_offset_s_,
                        c.exposure_time_s, c.right, &rig_xy);
  c.blackout = o.InBlackout(t_s);
  return c;
}

void StereoCamera::Finish(const StereoCapture& capture) {
  Develop(capture);
  // The auto-exposure meters the left image for the next frame.
  if (auto_exposure_ && !capture.blackout) {
    auto_exposure_->Update(auto_exposure_->Meter(*capture.left), 1.0 / rig_.options().rate_hz);
  }
}

void StereoCamera::Develop(const StereoCapture& c) const {
  const auto frame = static_cast<std::uint64_t>(c.index);
  if (!image_sensors_.empty()) {
    image_sensors_[0].Apply(c.sensor_exposure, noise_seed_, frame, c.left, c.gain,
                            c.clipped_render);
    image_sensors_[1].Apply(c.sensor_exposure, noise_seed_, frame, c.right, c.gain,
                            c.clipped_render);
  } else {
    const double noise_std = rig_.options().noise_std;
    ApplySensorModel(c.sensor_exposure * c.gain, noise_std, noise_seed_, frame, 0, c.left);
    ApplySensorModel(c.sensor_exposure * c.gain, noise_std, noise_seed_, frame, 1, c.right);
  }
  if (c.blackout) {
    std::fill(c.left->pixels.begin(), c.left->pixels.end(), 0);
    std::fill(c.right->pixels.begin(), c.right->pixels.end(), 0);
  }
}

}  // namespace trackbed::robot
