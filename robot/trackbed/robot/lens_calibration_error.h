// How far a lens's calibrated coefficients are from the lens as built. A calibration
// fits the lens model to points seen all over the image, so its coefficients' errors
// are not independent: a larger barrel term comes with a larger opposite higher-order
// term, and the calibrated model still puts points near where the lens does across the
// image it saw. Drawing each coefficient's published spread independently ignores that,
// and on a wide lens gives models that are not even monotonic inside the image (a
// published k2 spread comes from a camera whose image reaches a smaller radius, where
// k2 hardly matters).
//
// Here the error is drawn from the covariance the least-squares fit of the coefficients
// over the image gives them,
//
//   C = ε² · (2M / p) · (JᵀJ)⁻¹,
//
// where J is the 2M × p Jacobian of the M grid points' distorted pixel positions with
// respect to the p calibrated coefficients, at the lens as built, and ε is the
// calibration's accuracy stated once for any camera: the RMS over the image of the
// error in where the calibrated lens puts a point [px] (then E[|J δ|² / 2M] = ε²).
// A published calibration's coefficient spreads give its ε on its own camera's image
// (docs/calibration.md lists the values and how they were found).
#pragma once

#include <Eigen/Core>

#include "trackbed/common/pinhole_camera.h"
#include "trackbed/common/random.h"

namespace trackbed::robot {

/// The coefficients a calibration estimates, in the order of a drawn error: k1, k2, p1,
/// p2 of the radial–tangential model; k1, k2 of the equidistant model (its k3, k4 and
/// the radial–tangential k3 are given as built). None for an ideal pinhole.
int CalibratedLensCoefficients(geometry::LensModel model);

/// The covariance of the calibrated coefficients (CalibratedLensCoefficients' order, the
/// top-left p × p block; the rest zero) of `camera`'s lens calibrated to `rms_px`.
/// Throws std::invalid_argument when the lens cannot be inverted inside the image (the
/// check render::RenderCameraFor makes).
Eigen::Matrix4d LensCalibrationCovariance(const geometry::PinholeCamera& camera, double rms_px);

/// A drawn error of the coefficients (k1, k2, p1, p2; for the equidistant model p1 and
/// p2 are 0), four Gaussians from `g` whatever the lens; zero when `rms_px` is 0 or the
/// camera is an ideal pinhole.
Eigen::Vector4d DrawLensCalibrationError(random::Generator* g,
                                         const geometry::PinholeCamera& camera, double rms_px);

/// `lens` with the error `delta` (DrawLensCalibrationError's order) added.
geometry::LensDistortion WithCalibrationError(geometry::LensDistortion lens,
                                              const Eigen::Vector4d& delta);

}  // namespace trackbed::robot
