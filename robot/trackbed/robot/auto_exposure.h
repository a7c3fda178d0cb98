// A camera's auto-exposure and gain control (`robot.stereo.auto_exposure`): after each
// frame it meters the image's mean grey level and sets the next frame's exposure time
// and analog gain so that the mean approaches its target, as a first-order lag in the
// logarithm of the total exposure (exposure time × gain) with time constant τ:
//
//   E* = E · target / mean,   log E ← log E + (1 − e^(−Δt/τ)) · (log E* − log E)
//
// Exposure time comes first, up to its limit (longer exposures blur: the warp follows
// the time chosen, docs/camera_model.md), then gain up to its limit. The target and τ
// are settings of the controller, as a camera driver exposes them; the limits are the
// sensor's.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "trackbed/common/archive_eigen.h"
#include "trackbed/render/image.h"

namespace trackbed::robot {

/// `robot.stereo.auto_exposure`.
struct AutoExposureOptions {
  bool enabled = false;
  /// Mean grey level the controller holds the image at, in (0, 255).
  double target_grey = 128.0;
  /// Time constant of the control [s], > 0.
  double time_constant_s = 0.2;
  /// Exposure time limits [s], 0 < min <= max (max also at most the frame period).
  double min_exposure_s = 20e-6;
  double max_exposure_s = 15.3e-3;
  /// Largest analog gain, >= 1.
  double max_gain = 4.0;
  /// The metering window, [left, top, right, bottom] as fractions of the image's width
  /// and height, 0 <= left < right <= 1, 0 <= top < bottom <= 1: the mean is taken
  /// there, as a camera's auto-exposure region of interest (librealsense's
  /// rs2_set_region_of_interest). The whole image by default.
  Eigen::Vector4d metering_window{0.0, 0.0, 1.0, 1.0};

  /// Throws OptionError naming the first bad key.
  void Validate() const;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("enabled", &enabled);
    a->Visit("target_grey", &target_grey);
    a->Visit("time_constant_s", &time_constant_s);
    a->Visit("min_exposure_s", &min_exposure_s);
    a->Visit("max_exposure_s", &max_exposure_s);
    a->Visit("max_gain", &max_gain);
    a->Visit("metering_window", &metering_window);
  }
};

class AutoExposure {
 public:
  /// Starts at `initial_exposure_s` (clamped to the limits) and gain 1.
  AutoExposure(const AutoExposureOptions& options, double initial_exposure_s);

  double exposure_time_s() const { return exposure_s_; }
  double gain() const { return gain_; }

  /// The mean grey level of `image` over the metering window (0 for an empty image).
  double Meter(const GrayImage& image) const;

  /// The frame just taken with the current settings had mean grey level `mean_grey`;
  /// the next is `dt_s` later. A black frame (mean 0) counts as 0.5 grey levels.
  void Update(double mean_grey, double dt_s);

 private:
  AutoExposureOptions o_;
  double exposure_s_, gain_ = 1.0;
};

}  // namespace trackbed::robot
