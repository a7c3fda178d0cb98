// Stereo rig geometry and sensor model (see stereo_rig.h).
#include "trackbed/robot/stereo_rig.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/common/units.h"
#include "trackbed/render/sensor_warp.h"

namespace trackbed::robot {

void StereoRigOptions::ValidateLensCoversTheImage() const {
  // A lens whose distorted radius stops growing before the image's border leaves pixels
  // no ray reaches: the renderer, the calibration and the rectification all need every
  // pixel's ray (render::RenderCameraFor checks the border, where the extreme rays lie).
  geometry::PinholeCamera camera = DesignIntrinsics();
  camera.distortion = *distortion;
  try {
    render::RenderCameraFor(camera, 0);
  } catch (const std::invalid_argument& e) {
    std::string why = e.what();
    const std::string prefix = "RenderCameraFor: ";
    if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
    char image[96];
    std::snprintf(image, sizeof image, " of the %d x %d image at fx %.6g px", width_px, height_px,
                  camera.fx);
    throw OptionError("distortion", why + image);
  }
}

void StereoRigOptions::Validate() const {
  if (width_px < 16 || width_px > 8192) throw OptionError("width_px", "must be in [16, 8192]");
  if (height_px < 16 || height_px > 8192) throw OptionError("height_px", "must be in [16, 8192]");
  option_check::InRange("hfov_deg", hfov_deg, 10.0, 170.0);
  if (focal_length_px) {
    option_check::Positive("focal_length_px", *focal_length_px);
    // The same bound as hfov_deg's: the widest image side sees at most 170°.
    const double widest = 2.0 * std::atan(0.5 * std::max(width_px, height_px) / *focal_length_px);
    if (units::Degrees(widest) > 170.0) {
      throw OptionError("focal_length_px", "too short for the image: it would see more than 170°");
    }
  }
  if (principal_point_px) {
    option_check::InRange("principal_point_px[0]", principal_point_px->x(), 0.0, width_px - 1.0);
    option_check::InRange("principal_point_px[1]", principal_point_px->y(), 0.0, height_px - 1.0);
  }
  option_check::Positive("baseline_m", baseline_m);
  option_check::Finite("mount_m[0]", mount_m.x());
  option_check::Finite("mount_m[1]", mount_m.y());
  option_check::Finite("mount_m[2]", mount_m.z());
  option_check::InRange("pitch_down_deg", pitch_down_deg, -45.0, 60.0);
  option_check::InRange("rate_hz", rate_hz, 0.1, 1000.0);
  option_check::Positive("near_m", near_m);
  if (!(far_m > near_m)) throw OptionError("far_m", "must exceed near_m");
  option_check::Positive("exposure", exposure);
  option_check::NonNegative("noise_std", noise_std);
  option_check::InRange("exposure_time_s", exposure_time_s, 0.0, 1.0 / rate_hz);
  if (exposure_samples < 1 || exposure_samples > 64) {
    throw OptionError("exposure_samples",
                      "must be in [1, 64] (got " + std::to_string(exposure_samples) + ")");
  }
  if (distortion) {
    try {
      distortion->Validate();
    } catch (const OptionError& e) {
      throw OptionError("distortion." + e.field(), e.reason());
    }
    ValidateLensCoversTheImage();
  }
  if (rolling_shutter.line_delay_s) {
    // A frame's rows must all be read within the frame period.
    option_check::InRange("rolling_shutter.line_delay_s", *rolling_shutter.line_delay_s, 0.0,
                          1.0 / (rate_hz * height_px));
  }
  if (supersampling < 1 || supersampling > 4) {
    throw OptionError("supersampling",
                      "must be in [1, 4] (got " + std::to_string(supersampling) + ")");
  }
  if (edge_antialiasing_samples != 1 && edge_antialiasing_samples != 4) {
    throw OptionError("edge_antialiasing_samples",
                      "must be 1 (off) or 4, the sample counts the renderer draws (got " +
                          std::to_string(edge_antialiasing_samples) + ")");
  }
  photometric.Validate();
  if (auto_exposure.enabled) {
    auto_exposure.Validate();
    if (!(exposure_time_s > 0.0)) {
      throw OptionError("auto_exposure.enabled",
                        "needs exposure_time_s > 0: the exposure the render shows, the first "
                        "the controller sets");
    }
    option_check::InRange("auto_exposure.max_exposure_s", auto_exposure.max_exposure_s,
                          auto_exposure.min_exposure_s, 1.0 / rate_hz);
  }
  for (std::size_t k = 0; k < blackouts_s.size(); ++k) {
    const Eigen::Vector2d& b = blackouts_s[k];
    if (!(std::isfinite(b.x()) && std::isfinite(b.y()) && b.x() >= 0.0 && b.y() > 0.0)) {
      throw OptionError("blackouts_s[" + std::to_string(k) + "]",
                        "must be [start >= 0, duration > 0] in seconds");
    }
  }
}

geometry::PinholeCamera StereoRigOptions::DesignIntrinsics() const {
  geometry::PinholeCamera K =
      geometry::PinholeCamera::FromFieldOfView(width_px, height_px, units::Radians(hfov_deg));
  if (focal_length_px) K.fx = K.fy = *focal_length_px;
  if (principal_point_px) {
    K.cx = principal_point_px->x();
    K.cy = principal_point_px->y();
  }
  return K;
}

bool StereoRigOptions::InBlackout(double t_s) const {
  for (const Eigen::Vector2d& b : blackouts_s) {
    if (t_s >= b.x() && t_s < b.x() + b.y()) return true;
  }
  return false;
}

StereoRig::StereoRig(const StereoRigOptions& options) : options_(options) {
  options_.Validate();
  intrinsics_ = options_.DesignIntrinsics();
  // Camera axes in body axes for a level camera: z_cam = x_body, x_cam = −y_body,
  // y_cam = −z_body; then tilt down about the camera's x axis.
  Eigen::Matrix3d R_body_cam;
  R_body_cam.col(0) = -Eigen::Vector3d::UnitY();
  R_body_cam.col(1) = -Eigen::Vector3d::UnitZ();
  R_body_cam.col(2) = Eigen::Vector3d::UnitX();
  const double pitch = units::Radians(options_.pitch_down_deg);
  R_body_cam = R_body_cam * Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d half_baseline = 0.5 * options_.baseline_m * R_body_cam.col(0);
  T_body_left_.setIdentity();
  T_body_left_.linear() = R_body_cam;
  T_body_left_.translation() = options_.mount_m - half_baseline;
  T_body_right_ = T_body_left_;
  T_body_right_.translation() = options_.mount_m + half_baseline;
  right_intrinsics_ = intrinsics_;
}

StereoRig::StereoRig(const StereoRigOptions& options,
                     const calibration::StereoCalibration& as_built)
    : StereoRig(options) {
  as_built.Validate();
  if (as_built.width_px != options_.width_px || as_built.height_px != options_.height_px) {
    throw OptionError("width_px", "the rig as built must have the design's image size");
  }
  intrinsics_ = as_built.LeftCamera();
  right_intrinsics_ = as_built.RightCamera();
  T_body_left_ = as_built.T_body_left;
  T_body_right_ = as_built.T_body_right;
}

void ApplySensorModel(double exposure, double noise_std, std::uint64_t seed, std::uint64_t frame,
                      int camera, GrayImage* image) {
  if (exposure == 1.0 && noise_std == 0.0) return;
  // Noise values come from a table of 65536 samples of the Irwin–Hall sum of
  // four uniforms (zero mean, unit variance: close to Gaussian), indexed by a
  // xorshift64* stream keyed by (seed, frame, camera): 16 bits per pixel.
  // Cheap enough for 640 × 480 at hundreds of frames per second.
  // The table depends on (seed, noise_std) only: built once per thread and kept.
  constexpr int kTable = 1 << 16;
  struct NoiseTable {
    std::uint64_t seed = 0;
    double noise_std = -1.0;
    std::vector<float> values;
  };
  thread_local NoiseTable cached;
  if (cached.values.empty() || cached.seed != seed || cached.noise_std != noise_std) {
    cached.seed = seed;
    cached.noise_std = noise_std;
    cached.values.resize(kTable);
    std::uint64_t state = split_mix::Mix(seed ^ 0x5eed5eedULL);
    const double norm = 1.0 / (65536.0 * std::sqrt(4.0 / 12.0));
    for (float& t : cached.values) {
      state = split_mix::Mix(state);
      const double sum = static_cast<double>((state & 0xffff) + ((state >> 16) & 0xffff) +
                                             ((state >> 32) & 0xffff) + (state >> 48));
      t = static_cast<float>(noise_std * (sum - 2.0 * 65535.0) * norm);
    }
  }
  const float* table = cached.values.data();
  std::uint64_t x =
      split_mix::Mix(seed ^ split_mix::Mix(frame * 2 + static_cast<std::uint64_t>(camera))) | 1;
  const float gain = static_cast<float>(exposure);
  const bool noisy = noise_std > 0.0;
  std::uint8_t* px = image->pixels.data();
  const std::size_t n = image->pixels.size();
  // Blocks of 64 pixels: first their noise, four pixels per xorshift64* draw
  // (its 16-bit quarters from the low end), then the arithmetic on the block,
  // which the compiler vectorises; the bytes are those of pixel-by-pixel code
  // (build/tests/sensor_model_test).
  constexpr std::size_t kBlock = 64;
  float noise[kBlock] = {};
  for (std::size_t i0 = 0; i0 < n; i0 += kBlock) {
    const std::size_t m = std::min(kBlock, n - i0);
    for (std::size_t k = 0; k < m; k += 4) {
      x ^= x >> 12;
      x ^= x << 25;
      x ^= x >> 27;
      const std::uint64_t bits = x * 0x2545f4914f6cdd1dULL;
      if (noisy) {
        for (std::size_t q = 0; q < 4; ++q) noise[k + q] = table[(bits >> (16 * q)) & 0xffff];
      }
    }
    std::uint8_t* p = px + i0;
    for (std::size_t k = 0; k < m; ++k) {
      const float value = gain * static_cast<float>(p[k]) + noise[k] + 0.5f;
      p[k] = static_cast<std::uint8_t>(std::min(std::max(value, 0.0f), 255.0f));
    }
  }
}

}  // namespace trackbed::robot
