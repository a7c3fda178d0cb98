// The camera vocabulary every library shares: one pinhole camera (with its lens
// distortion) and one rectified stereo pair. OpenCV conventions: camera x right,
// y down, z forward; pixel (u, v) = (0, 0) is the centre of the top-left pixel.
#pragma once

#include <Eigen/Core>

namespace trackbed::geometry {

/// The lens models a calibration names (OpenCV's and Kalibr's): none (an ideal
/// pinhole), radial–tangential (`radtan`, Brown 1966 and Conrady 1919; OpenCV's
/// `k1, k2, p1, p2, k3`, Bouguet's toolbox) and equidistant (Kannala & Brandt 2006;
/// OpenCV's fisheye module, Kalibr's `equidistant`).
enum class LensModel { kNone, kRadialTangential, kEquidistant };

/// A lens's distortion: it maps undistorted normalized image coordinates
/// (x, y) = (X/Z, Y/Z) to distorted ones. Radial–tangential:
///   r² = x² + y²,  radial = 1 + k1 r² + k2 r⁴ + k3 r⁶,
///   x_d = x·radial + 2 p1 x y + p2 (r² + 2x²),
///   y_d = y·radial + p1 (r² + 2y²) + 2 p2 x y.
/// Equidistant: θ = atan(r), θ_d = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸),
///   (x_d, y_d) = (θ_d / r) (x, y).
/// kNone, or all coefficients zero under radial–tangential, is an ideal pinhole.
struct LensDistortion {
  LensModel model = LensModel::kNone;
  double k1 = 0.0, k2 = 0.0, k3 = 0.0;  ///< radial coefficients (both models)
  double k4 = 0.0;                      ///< equidistant only
  double p1 = 0.0, p2 = 0.0;            ///< tangential (decentring), radial–tangential only

  /// A radial–tangential lens with OpenCV's coefficients.
  static LensDistortion RadialTangential(double k1, double k2, double p1, double p2,
                                         double k3 = 0.0);
  /// An equidistant (fisheye) lens.
  static LensDistortion Equidistant(double k1, double k2, double k3, double k4);

  /// Whether the lens maps every point to itself (an equidistant lens never does: its
  /// θ is not tan θ).
  bool is_zero() const;
  /// Distorted normalized coordinates of undistorted `xy`.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xy) const;
  /// Undistorted normalized coordinates of distorted `xy_d`: Newton's method from
  /// `xy_d`, until the step is below 1e-14 or 50 iterations.
  Eigen::Vector2d Undistort(const Eigen::Vector2d& xy_d) const;
  /// Throws OptionError naming the first invalid coefficient (not finite, or set for
  /// the other model).
  void Validate() const;

  bool operator==(const LensDistortion& o) const {
    return model == o.model && k1 == o.k1 && k2 == o.k2 && k3 == o.k3 && k4 == o.k4 && p1 == o.p1 &&
           p2 == o.p2;
  }
  bool operator!=(const LensDistortion& o) const { return !(*this == o); }

  /// The keys of `robot.stereo.distortion` and of a calibration file's `distortion`.
  template <class Archive>
  void Serialize(Archive* a) {
    a->VisitEnum("model", &model,
                 {{"none", LensModel::kNone},
                  {"radial_tangential", LensModel::kRadialTangential},
                  {"equidistant", LensModel::kEquidistant}});
    a->Visit("k1", &k1);
    a->Visit("k2", &k2);
    a->Visit("k3", &k3);
    a->Visit("k4", &k4);
    a->Visit("p1", &p1);
    a->Visit("p2", &p2);
  }
};

/// A pinhole camera: image size, focal lengths and principal point [px], and its lens.
struct PinholeCamera {
  int width_px = 0;
  int height_px = 0;
  double fx = 0.0;  ///< focal lengths [px], > 0
  double fy = 0.0;
  double cx = 0.0;  ///< principal point [px], finite
  double cy = 0.0;
  LensDistortion distortion;  ///< none: an ideal pinhole

  /// Pixel of a point in camera coordinates (z > 0), through the lens.
  Eigen::Vector2d Project(const Eigen::Vector3d& p_camera) const;
  /// The point at depth z [m] along the optical axis that projects to pixel (u, v);
  /// undistorts first when the lens is not ideal.
  Eigen::Vector3d Backproject(double u, double v, double z) const;
  /// The intrinsic matrix K = [fx 0 cx; 0 fy cy; 0 0 1].
  Eigen::Matrix3d K() const;

  /// Throws OptionError naming the first invalid field (width_px, height_px > 0;
  /// fx, fy > 0 and finite; cx, cy finite).
  void Validate() const;

  /// Square pixels, principal point at the image centre, horizontal field of view
  /// `hfov_rad`, no distortion.
  static PinholeCamera FromFieldOfView(int width_px, int height_px, double hfov_rad);
};

}  // namespace trackbed::geometry
