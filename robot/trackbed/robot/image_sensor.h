// The image sensor in electrons (`robot.stereo.photometric`): what turns the light on
// each pixel into a grey level, with the noise a datasheet or an EMVA 1288 report
// gives (docs/camera_model.md).
//
//   signal  = (render grey / 255) · exposure · vignetting(r) · full well     [e⁻]
//   charge  = signal · (1 + PRNU_pixel) + DSNU_pixel + shot + read          [e⁻]
//   shot    ~ normal(0, signal)      (Poisson's variance, drawn as its normal
//                                     approximation: exact in mean and variance)
//   read    ~ normal(0, read_noise²)
//   DN      = clamp(round(charge · gain / full well · (2^adc_bits − 1)))    [ADC]
//   grey    = round(DN · 255 / (2^adc_bits − 1))                             [8 bits]
//
// The render's grey is scene radiance on a scale where 255 at exposure 1 fills the
// well: the rendered scene is exposed as the fixed-exposure camera shows it.
// vignetting(r) = 1 + (corner − 1) r², r the distance from the image centre over the
// half diagonal (the even polynomial of Alexandrov et al. 2016 to its first term).
// PRNU (gain) and DSNU (offset) are each pixel's own, fixed per camera; shot and read
// noise are drawn per frame from a generator keyed by (seed, frame, camera), so every
// image is reproducible on its own.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "trackbed/common/archive.h"
#include "trackbed/render/image.h"

namespace trackbed::robot {

/// `robot.stereo.photometric`. Absent keys: the realism profile's.
struct PhotometricOptions {
  /// Whether the electron model replaces the grey-level one (`exposure`, `noise_std`).
  std::optional<bool> enabled;
  std::optional<double> full_well_e;        ///< saturation capacity [e⁻], > 0
  std::optional<double> read_noise_e;       ///< temporal dark noise [e⁻], >= 0
  std::optional<double> prnu_std;           ///< photo-response non-uniformity [-], >= 0
  std::optional<double> dsnu_std_e;         ///< dark signal non-uniformity [e⁻], >= 0
  std::optional<int> adc_bits;              ///< ADC resolution, in [8, 16]
  std::optional<double> vignetting_corner;  ///< relative illumination at a corner, (0, 1]
  std::optional<double> gain;               ///< analog gain [-], >= 1

  void Validate() const;

  template <class Archive>
  void Serialize(Archive* a) {
    constexpr archive::Field kOpt = archive::kOmitEmpty;
    a->Visit("enabled", &enabled, kOpt);
    a->Visit("full_well_e", &full_well_e, kOpt);
    a->Visit("read_noise_e", &read_noise_e, kOpt);
    a->Visit("prnu_std", &prnu_std, kOpt);
    a->Visit("dsnu_std_e", &dsnu_std_e, kOpt);
    a->Visit("adc_bits", &adc_bits, kOpt);
    a->Visit("vignetting_corner", &vignetting_corner, kOpt);
    a->Visit("gain", &gain, kOpt);
  }
};

/// One camera's sensor: holds its fixed pattern (PRNU, DSNU) and vignetting for its
/// image size.
class ImageSensor {
 public:
  /// `options` resolved (every key set, enabled). Throws OptionError for a bad value.
  ImageSensor(const PhotometricOptions& options, int width_px, int height_px, std::uint64_t seed,
              int camera);

  /// Turns a render into the camera's image in place (`exposure` scales the light as
  /// StereoRigOptions::exposure; `gain` multiplies the configured analog gain, as an
  /// auto-exposure sets it). `clipped_render`: the render was exposed before its 8 bits
  /// clipped (scene lighting), so a render pixel at 255 stands for light at or above the
  /// full well, however far: the pixel reads as a full well, which neither vignetting nor
  /// noise lowers.
  void Apply(double exposure, std::uint64_t seed, std::uint64_t frame, GrayImage* image,
             double gain = 1.0, bool clipped_render = false) const;

  /// The electrons one grey level of the output stands for [e⁻ per grey level].
  double electrons_per_grey() const;

 private:
  PhotometricOptions o_;
  int width_, height_, camera_;
  std::vector<float> gain_map_;    // vignetting · (1 + PRNU), per pixel
  std::vector<float> offset_map_;  // DSNU [e⁻], per pixel
};

}  // namespace trackbed::robot
