// What a real camera's pixels see of the renderer's image. The renderer draws an ideal
// pinhole taking an instant (a rasteriser draws straight lines straight and has one
// pose per frame); a real camera's pixels see the scene through a lens (distortion),
// a rolling shutter exposes each row at its own time, and every row integrates over
// the time its shutter is open (motion blur). All three are one backward warp of a
// global-shutter render by its depth buffer:
//
//   for each sensor pixel s, at each of N instants t_k of its row's exposure:
//     p0 = the render pixel of s's ray (through the lens, once per run);
//     find q in the render with  project(A(t_k) · X(q)) = p0,
//     where X(q) is the rendered point at q (its ray at the depth buffer's depth) and
//     A(t) the camera's motion from the render's instant to t;
//   pixel = the mean over k of the render's mean over s's footprint about q.
//
// The footprint is the box the pixel's four corners span in the render through the
// lens: a real pixel integrates the light over its area, so where the lens compresses
// the view a pixel averages several render pixels rather than picking one, which
// aliases (a summed-area table of the render makes each mean four lookups).
//
// q is found by the fixed-point iteration q ← q + p0 − project(A · X(q)): one step from
// the left neighbour's shift for the first instant (three at a row's start), one from
// the previous instant's q after it:
// exact where the depth is smooth, wrong by up to the parallax across a depth edge,
// which is what a per-band render would get right (sensor_warp_test states the error
// against per-band renders). Sky (infinite depth) moves by the rotation only.
//
// Row v of an H-row sensor is exposed around t + (v − (H − 1)/2) · line_delay: the
// frame's stamp is its middle row's, so a global shutter (line delay 0) keeps the
// stamp it had. Render pixels outside the render take the nearest edge pixel.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/common/pinhole_camera.h"
#include "trackbed/render/image.h"

namespace trackbed::render {

/// How a frame is exposed.
struct SensorTiming {
  double exposure_time_s = 0.0;  ///< shutter open time per row [s], >= 0
  int samples = 1;               ///< instants averaged over the exposure, in [1, 64]
  double line_delay_s = 0.0;     ///< rolling shutter: row-to-row delay [s], >= 0

  /// Whether the image is an instant for every row (no warp in time).
  bool instant() const { return exposure_time_s == 0.0 && line_delay_s == 0.0; }
};

/// The pinhole camera to render for `sensor` (with its lens): the same focal lengths,
/// wide and tall enough that every sensor pixel's ray falls at least `margin_px` inside
/// it. The sensor camera itself when its lens is ideal and the margin 0. Throws
/// std::invalid_argument when the lens's field of view cannot be drawn by a pinhole
/// (beyond 160° across, where the render would grow without bound).
geometry::PinholeCamera RenderCameraFor(const geometry::PinholeCamera& sensor, int margin_px);

/// `camera` drawn `factor` times as finely (factor × factor render pixels per pixel,
/// the render camera's pixel (u, v) covering the supersampled pixels from factor·u to
/// factor·u + factor − 1): a sensor pixel then takes the mean of the renders' pixels it
/// covers rather than one point of the scene, as a real pixel integrates over its area.
/// `factor` in [1, 4]; 1 returns `camera`.
geometry::PinholeCamera Supersampled(const geometry::PinholeCamera& camera, int factor);

/// `camera` grown to `width_px` × `height_px` (at least its size) about the same rays:
/// the principal point moves by half the growth, rounded down.
geometry::PinholeCamera GrownTo(const geometry::PinholeCamera& camera, int width_px, int height_px);

/// The camera's motion from the render's instant to `dt_s` later: the map from the
/// camera's coordinates at the render to its coordinates at `dt_s`.
using CameraMotion = std::function<Eigen::Isometry3d(double dt_s)>;

/// Warps renders of `render` into images of `sensor`. Holds the lens's pixel map; not
/// copyable.
class SensorWarp {
 public:
  /// Throws std::invalid_argument when `render` does not cover `sensor`'s rays.
  SensorWarp(const geometry::PinholeCamera& sensor, const geometry::PinholeCamera& render);
  SensorWarp(const SensorWarp&) = delete;
  SensorWarp& operator=(const SensorWarp&) = delete;

  const geometry::PinholeCamera& sensor() const { return sensor_; }
  const geometry::PinholeCamera& render() const { return render_; }
  /// Whether the sensor's image is the render itself (an ideal lens, the same camera).
  bool identity() const { return identity_; }

  /// The sensor's image of a render taken at `motion(0)`: through the lens only when
  /// `timing.instant()` (then `depth` may be null), else warped in time too.
  void Apply(const GrayImage& rendered, const DepthImage* depth, const CameraMotion& motion,
             const SensorTiming& timing, GrayImage* out);

 private:
  // Sensor pixel (u, v) [px, may be fractional] as a point of the render.
  Eigen::Vector2d RenderPoint(double u, double v) const;
  void BuildFootprints();
  void ApplyLens(const GrayImage& rendered, GrayImage* out);

  geometry::PinholeCamera sensor_, render_;
  bool identity_ = false;
  // Each sensor pixel's ray as a render pixel (row-major, sensor size).
  std::vector<float> map_u_, map_v_;
  // Each sensor pixel's footprint in the render: the half-sizes [render px] of the box
  // its four corners span (0.5, one render pixel, near the centre of a lens drawn at
  // the sensor's focal length; more where the lens compresses the view).
  std::vector<float> half_u_, half_v_;
  // The render's summed-area table (BuildSummedArea in the source).
  std::vector<std::uint32_t> sat_;
  std::vector<float> sum_, inverse_depth_;
  std::vector<float> q_u_, q_v_;
};

}  // namespace trackbed::render
