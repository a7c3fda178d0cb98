// Two-view geometry, scale ratio, patch matching and path offsets (see
// teach_repeat_geometry.h).
#include "trackbed/teach_repeat/teach_repeat_geometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/SVD>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "trackbed/common/median.h"
#include "trackbed/common/option_error.h"
#include "trackbed/common/pose2.h"
#include "trackbed/common/se3.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::teach_repeat {
namespace {

Eigen::Vector2d Normalised(const geometry::PinholeCamera& c, const cv::Point2f& p) {
  return {(p.x - c.cx) / c.fx, (p.y - c.cy) / c.fy};
}

double PixelDistance(const geometry::PinholeCamera& c, const Eigen::Vector3d& p_cam,
                     const cv::Point2f& z) {
  const double u = c.fx * p_cam.x() / p_cam.z() + c.cx;
  const double v = c.fy * p_cam.y() / p_cam.z() + c.cy;
  return std::hypot(u - z.x, v - z.y);
}

/// Mean and standard deviation of a CV_8UC1 window.
void MeanStd(const cv::Mat& window, double* mean, double* stddev) {
  double sum = 0.0, sum_sq = 0.0;
  for (int r = 0; r < window.rows; ++r) {
    const unsigned char* row = window.ptr<unsigned char>(r);
    for (int c = 0; c < window.cols; ++c) {
      sum += row[c];
      sum_sq += static_cast<double>(row[c]) * row[c];
    }
  }
  const double n = static_cast<double>(window.rows) * window.cols;
  *mean = sum / n;
  *stddev = std::sqrt(std::max(0.0, sum_sq / n - *mean * *mean));
}

/// Offset of the vertex of the parabola through (−1, a), (0, b), (1, c), in [−0.5, 0.5].
double ParabolaPeak(double a, double b, double c) {
  const double denominator = a - 2.0 * b + c;
  if (!(denominator < 0.0)) return 0.0;  // not a maximum
  return std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
}

/// Sampson residuals (signed, normalised image units) of x_b ᵀ [t]× R x_a = 0.
void SampsonResiduals(const std::vector<Eigen::Vector3d>& xa,
                      const std::vector<Eigen::Vector3d>& xb, const Eigen::Matrix3d& R,
                      const Eigen::Vector3d& t, Eigen::VectorXd* r) {
  const Eigen::Matrix3d E = geometry::Skew(t) * R;
  r->resize(static_cast<Eigen::Index>(xa.size()));
  for (std::size_t i = 0; i < xa.size(); ++i) {
    const Eigen::Vector3d Ea = E * xa[i];
    const Eigen::Vector3d Eb = E.transpose() * xb[i];
    const double denominator =
        Ea.x() * Ea.x() + Ea.y() * Ea.y() + Eb.x() * Eb.x() + Eb.y() * Eb.y();
    (*r)(static_cast<Eigen::Index>(i)) =
        denominator > 0.0 ? xb[i].dot(Ea) / std::sqrt(denominator) : 0.0;
  }
}

/// Levenberg–Marquardt on the Sampson error of the inliers over the 5 degrees of freedom
/// of (R, t/|t|): R ← Exp(ω)·R, t ← normalise(t + β₁b₁ + β₂b₂) with b₁, b₂ ⟂ t. RANSAC's
/// answer comes from a minimal sample; refitting on all inliers makes the reprojection
/// error a property of the tracks rather than of the sample drawn.
void RefineRelativePose(const std::vector<Eigen::Vector3d>& xa,
                        const std::vector<Eigen::Vector3d>& xb, Eigen::Matrix3d* R,
                        Eigen::Vector3d* t) {
  constexpr int kIterations = 10;
  constexpr double kStep = 1e-7;
  auto apply = [](const Eigen::Matrix<double, 5, 1>& d, const Eigen::Matrix3d& R0,
                  const Eigen::Vector3d& t0, Eigen::Matrix3d* R1, Eigen::Vector3d* t1) {
    const Eigen::Vector3d w = d.head<3>();
    *R1 = geometry::ExpSO3(w) * R0;
    Eigen::Vector3d b1 = t0.unitOrthogonal();
    Eigen::Vector3d b2 = t0.normalized().cross(b1);
    *t1 = (t0 + d(3) * b1 + d(4) * b2).normalized();
  };
  Eigen::VectorXd r, r_try;
  SampsonResiduals(xa, xb, *R, *t, &r);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  for (int it = 0; it < kIterations; ++it) {
    Eigen::MatrixXd J(r.size(), 5);
    for (int k = 0; k < 5; ++k) {
      Eigen::Matrix<double, 5, 1> d = Eigen::Matrix<double, 5, 1>::Zero();
      d(k) = kStep;
      Eigen::Matrix3d R1;
      Eigen::Vector3d t1;
      apply(d, *R, *t, &R1, &t1);
      SampsonResiduals(xa, xb, R1, t1, &r_try);
      J.col(k) = (r_try - r) / kStep;
    }
    const Eigen::Matrix<double, 5, 5> H = J.transpose() * J;
    const Eigen::Matrix<double, 5, 1> g = J.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 5 && !improved; ++attempt) {
      Eigen::Matrix<double, 5, 5> A = H;
      A.diagonal() *= 1.0 + lambda;
      const Eigen::Matrix<double, 5, 1> d = A.ldlt().solve(-g);
      if (!d.allFinite()) break;
      Eigen::Matrix3d R1;
      Eigen::Vector3d t1;
      apply(d, *R, *t, &R1, &t1);
      SampsonResiduals(xa, xb, R1, t1, &r_try);
      const double c = r_try.squaredNorm();
      if (c < cost) {
        *R = R1;
        *t = t1;
        r = r_try;
        improved = cost - c > 1e-12 * cost;
        cost = c;
        lambda = std::max(1e-9, lambda / 10.0);
        if (!improved) return;  // converged
        improved = true;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) return;
  }
}

}  // namespace

void TwoViewOptions::Validate() const {
  option_check::Positive("ransac_threshold_px", ransac_threshold_px);
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw OptionError("confidence",
                      "must be in (0, 1) (got " + option_check::Describe(confidence) + ")");
  }
  if (max_iterations < 1) {
    throw OptionError("max_iterations",
                      "must be >= 1 (got " + std::to_string(max_iterations) + ")");
  }
  if (min_inliers < 5) {
    throw OptionError("min_inliers", "must be >= 5 (got " + std::to_string(min_inliers) + ")");
  }
}

Eigen::Vector3d TriangulateLinear(const Eigen::Vector2d& x_a, const Eigen::Vector2d& x_b,
                                  const Eigen::Isometry3d& T_b_a) {
  // Hartley & Zisserman §12.2: x × (P X) = 0, two rows per view, solved by SVD.
  Eigen::Matrix<double, 3, 4> Pa = Eigen::Matrix<double, 3, 4>::Zero();
  Pa.leftCols<3>().setIdentity();
  const Eigen::Matrix<double, 3, 4> Pb = T_b_a.matrix().topRows<3>();
  Eigen::Matrix4d A;
  A.row(0) = x_a.x() * Pa.row(2) - Pa.row(0);
  A.row(1) = x_a.y() * Pa.row(2) - Pa.row(1);
  A.row(2) = x_b.x() * Pb.row(2) - Pb.row(0);
  A.row(3) = x_b.y() * Pb.row(2) - Pb.row(1);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (X.w() == 0.0) return Eigen::Vector3d::Zero();
  return X.head<3>() / X.w();
}

TwoViewGeometry ReconstructTwoView(const geometry::PinholeCamera& camera,
                                   const std::vector<cv::Point2f>& a,
                                   const std::vector<cv::Point2f>& b, double scale_m,
                                   const TwoViewOptions& options) {
  if (a.size() != b.size()) {
    throw std::invalid_argument("ReconstructTwoView: " + std::to_string(a.size()) +
                                " points in a, " + std::to_string(b.size()) + " in b");
  }
  camera.Validate();
  options.Validate();
  TwoViewGeometry g;
  const std::size_t n = a.size();
  g.p_a.assign(n, Eigen::Vector3d::Zero());
  g.inlier.assign(n, 0);
  std::vector<double> parallax(n);
  for (std::size_t i = 0; i < n; ++i) parallax[i] = std::hypot(b[i].x - a[i].x, b[i].y - a[i].y);
  g.median_parallax_px = Median(parallax);
  if (static_cast<int>(n) < options.min_inliers) {
    g.reason = "too few correspondences (" + std::to_string(n) + ")";
    return g;
  }

  const cv::Mat K(perception::CvCameraMatrix(camera));
  cv::Mat mask;
  cv::Mat E = cv::findEssentialMat(a, b, K, cv::RANSAC, options.confidence,
                                   options.ransac_threshold_px, options.max_iterations, mask);
  if (E.rows < 3 || E.cols != 3) {
    g.reason = "no essential matrix (degenerate configuration)";
    return g;
  }
  E = E.rowRange(0, 3).clone();  // with few points several solutions may be stacked
  cv::Mat R_cv, t_cv, triangulated;
  // A large distance threshold: recoverPose's default (50 baselines) would reject every
  // point of a short baseline as "at infinity"; we check depths ourselves below.
  cv::recoverPose(E, a, b, K, R_cv, t_cv, 1e6, mask, triangulated);
  Eigen::Matrix3d R_b_a;
  Eigen::Vector3d t_b_a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_b_a(r, c) = R_cv.at<double>(r, c);
    t_b_a(r) = t_cv.at<double>(r, 0);
  }
  if (!R_b_a.allFinite() || !t_b_a.allFinite() || t_b_a.norm() == 0.0) {
    g.reason = "pose recovery failed";
    return g;
  }
  if (options.refine) {
    std::vector<Eigen::Vector3d> xa, xb;
    for (std::size_t i = 0; i < n; ++i) {
      if (!mask.at<unsigned char>(static_cast<int>(i))) continue;
      xa.push_back(Normalised(camera, a[i]).homogeneous());
      xb.push_back(Normalised(camera, b[i]).homogeneous());
    }
    t_b_a.normalize();
    if (xa.size() >= 5) RefineRelativePose(xa, xb, &R_b_a, &t_b_a);
  }
  const double scale = scale_m > 0.0 ? scale_m : 1.0;
  t_b_a *= scale / t_b_a.norm();
  Eigen::Isometry3d T_b_a = Eigen::Isometry3d::Identity();
  T_b_a.linear() = R_b_a;
  T_b_a.translation() = t_b_a;

  double error_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!mask.at<unsigned char>(static_cast<int>(i))) continue;
    const Eigen::Vector3d p_a =
        TriangulateLinear(Normalised(camera, a[i]), Normalised(camera, b[i]), T_b_a);
    const Eigen::Vector3d p_b = T_b_a * p_a;
    if (!(p_a.z() > 0.0 && p_b.z() > 0.0) || !p_a.allFinite()) continue;
    g.p_a[i] = p_a;
    g.inlier[i] = 1;
    ++g.inliers;
    error_sum += 0.5 * (PixelDistance(camera, p_a, a[i]) + PixelDistance(camera, p_b, b[i]));
  }
  if (g.inliers < options.min_inliers) {
    g.reason = "too few inliers in front of both cameras (" + std::to_string(g.inliers) + ")";
    g.inliers = 0;
    std::fill(g.inlier.begin(), g.inlier.end(), 0);
    std::fill(g.p_a.begin(), g.p_a.end(), Eigen::Vector3d::Zero());
    return g;
  }
  g.reprojection_error_px = error_sum / g.inliers;
  g.T_a_b = T_b_a.inverse();
  g.ok = true;
  return g;
}

std::optional<double> ScaleRatio(const std::vector<Eigen::Vector3d>& reference,
                                 const std::vector<Eigen::Vector3d>& unscaled,
                                 const std::vector<unsigned char>& mask) {
  if (reference.size() != unscaled.size() || (!mask.empty() && mask.size() != reference.size())) {
    throw std::invalid_argument("ScaleRatio: reference, unscaled and mask differ in size");
  }
  std::vector<double> ratios;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const double r = reference[i].norm(), u = unscaled[i].norm();
    if (r > 0.0 && u > 0.0 && std::isfinite(r / u)) ratios.push_back(r / u);
  }
  if (ratios.empty()) return std::nullopt;
  return Median(std::move(ratios));
}

std::optional<cv::Point2d> ProjectPoint(const geometry::PinholeCamera& camera,
                                        const Eigen::Vector3d& p_cam, double min_depth_m) {
  if (!(p_cam.z() > min_depth_m)) return std::nullopt;
  return cv::Point2d(camera.fx * p_cam.x() / p_cam.z() + camera.cx,
                     camera.fy * p_cam.y() / p_cam.z() + camera.cy);
}

std::optional<double> Zncc(const cv::Mat& patch, const cv::Mat& image, cv::Point centre,
                           double min_stddev) {
  const int h = patch.rows / 2;
  const cv::Rect window(centre.x - h, centre.y - h, patch.cols, patch.rows);
  if (window.x < 0 || window.y < 0 || window.x + window.width > image.cols ||
      window.y + window.height > image.rows) {
    return std::nullopt;
  }
  const cv::Mat w = image(window);
  double pm, ps, wm, ws;
  MeanStd(patch, &pm, &ps);
  MeanStd(w, &wm, &ws);
  if (ps < min_stddev || ws < min_stddev) return 0.0;
  double sum = 0.0;
  for (int r = 0; r < patch.rows; ++r) {
    const unsigned char* pr = patch.ptr<unsigned char>(r);
    const unsigned char* wr = w.ptr<unsigned char>(r);
    for (int c = 0; c < patch.cols; ++c) sum += (pr[c] - pm) * (wr[c] - wm);
  }
  return sum / (static_cast<double>(patch.rows) * patch.cols * ps * ws);
}

PatchMatch SearchPatch(const cv::Mat& image, const cv::Mat& patch, cv::Point2f predicted,
                       int radius_px, double min_stddev) {
  PatchMatch best;
  if (!std::isfinite(predicted.x) || !std::isfinite(predicted.y)) return best;
  const int cx = static_cast<int>(std::lround(predicted.x));
  const int cy = static_cast<int>(std::lround(predicted.y));
  const int side = 2 * radius_px + 1;
  std::vector<double> scores(static_cast<std::size_t>(side * side), -2.0);
  int best_dx = 0, best_dy = 0;
  for (int dy = -radius_px; dy <= radius_px; ++dy) {
    for (int dx = -radius_px; dx <= radius_px; ++dx) {
      const std::optional<double> s = Zncc(patch, image, {cx + dx, cy + dy}, min_stddev);
      if (!s) continue;
      scores[static_cast<std::size_t>((dy + radius_px) * side + dx + radius_px)] = *s;
      if (!best.found || *s > best.score) {
        best.found = true;
        best.score = *s;
        best_dx = dx;
        best_dy = dy;
      }
    }
  }
  if (!best.found) return best;
  auto at = [&](int dx, int dy) -> double {
    if (std::abs(dx) > radius_px || std::abs(dy) > radius_px) return -2.0;
    return scores[static_cast<std::size_t>((dy + radius_px) * side + dx + radius_px)];
  };
  double sx = 0.0, sy = 0.0;
  const double left = at(best_dx - 1, best_dy), right = at(best_dx + 1, best_dy);
  const double up = at(best_dx, best_dy - 1), down = at(best_dx, best_dy + 1);
  if (left > -2.0 && right > -2.0) sx = ParabolaPeak(left, best.score, right);
  if (up > -2.0 && down > -2.0) sy = ParabolaPeak(up, best.score, down);
  best.position =
      cv::Point2f(static_cast<float>(cx + best_dx + sx), static_cast<float>(cy + best_dy + sy));
  return best;
}

cv::Point2f EstimateImageShift(const cv::Mat& from, const cv::Mat& to) {
  if (from.empty() || from.size() != to.size() || from.type() != CV_8UC1 || to.type() != CV_8UC1) {
    throw std::invalid_argument("EstimateImageShift: needs two CV_8UC1 images of one size");
  }
  cv::Mat a, b, window;
  from.convertTo(a, CV_64F);
  to.convertTo(b, CV_64F);
  cv::createHanningWindow(window, from.size(), CV_64F);
  const cv::Point2d shift = cv::phaseCorrelate(a, b, window);
  return {static_cast<float>(shift.x), static_cast<float>(shift.y)};
}

double CameraHeading(const Eigen::Matrix3d& R_a_cam) {
  const Eigen::Vector3d axis = R_a_cam.col(2);  // optical axis in a
  return std::atan2(-axis.x(), axis.z());
}

PathOffset ComputePathOffset(const Eigen::Isometry3d& T_first_cam,
                             const Eigen::Isometry3d& T_first_last) {
  // Horizontal plane of the first camera: forward = z, left = −x.
  const Eigen::Vector2d end(T_first_last.translation().z(), -T_first_last.translation().x());
  const Eigen::Vector2d p(T_first_cam.translation().z(), -T_first_cam.translation().x());
  PathOffset o;
  o.segment_length_m = end.norm();
  const double end_heading = CameraHeading(T_first_last.linear());
  Eigen::Vector2d direction(1.0, 0.0);
  if (o.segment_length_m >= 1e-3) {
    direction = end / o.segment_length_m;
    o.progress = direction.dot(p) / o.segment_length_m;
  }
  o.lateral_m = direction.x() * p.y() - direction.y() * p.x();
  const double reference = std::clamp(o.progress, 0.0, 1.0) * end_heading;
  o.heading_rad = geometry::WrapAngle(CameraHeading(T_first_cam.linear()) - reference);
  return o;
}

}  // namespace trackbed::teach_repeat
