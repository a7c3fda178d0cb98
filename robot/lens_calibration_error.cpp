// A lens's calibration error drawn from the least-squares covariance of its
// coefficients over the image (see lens_calibration_error.h).
#include "trackbed/robot/lens_calibration_error.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "trackbed/render/sensor_warp.h"

namespace trackbed::robot {
namespace {

// The grid of points a calibration is taken to have seen: evenly over the image.
constexpr int kGridColumns = 64, kGridRows = 48;

// The lens with calibrated coefficient `i` (CalibratedLensCoefficients' order) moved by
// `step`.
geometry::LensDistortion Moved(geometry::LensDistortion lens, int i, double step) {
  double* coefficient[] = {&lens.k1, &lens.k2, &lens.p1, &lens.p2};
  *coefficient[i] += step;
  return lens;
}

}  // namespace

int CalibratedLensCoefficients(geometry::LensModel model) {
  switch (model) {
    case geometry::LensModel::kNone:
      return 0;
    case geometry::LensModel::kRadialTangential:
      return 4;
    case geometry::LensModel::kEquidistant:
      return 2;
  }
  return 0;
}

Eigen::Matrix4d LensCalibrationCovariance(const geometry::PinholeCamera& camera, double rms_px) {
  const geometry::LensDistortion& lens = camera.distortion;
  const int p = CalibratedLensCoefficients(lens.model);
  Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
  if (p == 0 || rms_px == 0.0) return C;
  render::RenderCameraFor(camera, 0);  // throws unless every pixel's ray can be found
  // Both models are linear in their coefficients (x_d = x·(1 + k1 r² + …) + tangential
  // terms; θ_d = θ·(1 + k1 θ² + …)), so a unit step gives the Jacobian's column exactly.
  Eigen::MatrixXd JtJ = Eigen::MatrixXd::Zero(p, p);
  for (int row = 0; row < kGridRows; ++row) {
    for (int col = 0; col < kGridColumns; ++col) {
      const double u = (col + 0.5) * camera.width_px / kGridColumns - 0.5;
      const double v = (row + 0.5) * camera.height_px / kGridRows - 0.5;
      const Eigen::Vector2d d((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy);
      const Eigen::Vector2d xy = lens.Undistort(d);
      Eigen::Matrix<double, 2, Eigen::Dynamic> J(2, p);
      for (int i = 0; i < p; ++i) {
        const Eigen::Vector2d column = Moved(lens, i, 1.0).Distort(xy) - d;
        J.col(i) = Eigen::Vector2d(camera.fx * column.x(), camera.fy * column.y());
      }
      JtJ += J.transpose() * J;
    }
  }
  const double rows = 2.0 * kGridColumns * kGridRows;
  C.topLeftCorner(p, p) = rms_px * rms_px * (rows / p) * JtJ.inverse();
  return C;
}

Eigen::Vector4d DrawLensCalibrationError(random::Generator* g,
                                         const geometry::PinholeCamera& camera, double rms_px) {
  Eigen::Vector4d z;
  for (int i = 0; i < 4; ++i) z[i] = g->Gaussian();
  const int p = CalibratedLensCoefficients(camera.distortion.model);
  if (p == 0 || rms_px == 0.0) return Eigen::Vector4d::Zero();
  const Eigen::Matrix4d C = LensCalibrationCovariance(camera, rms_px);
  Eigen::Vector4d delta = Eigen::Vector4d::Zero();
  delta.head(p) = C.topLeftCorner(p, p).llt().matrixL() * z.head(p);
  return delta;
}

geometry::LensDistortion WithCalibrationError(geometry::LensDistortion lens,
                                              const Eigen::Vector4d& delta) {
  const int p = CalibratedLensCoefficients(lens.model);
  for (int i = 0; i < p; ++i) lens = Moved(lens, i, delta[i]);
  return lens;
}

}  // namespace trackbed::robot
