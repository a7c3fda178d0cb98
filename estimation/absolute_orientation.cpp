// Horn's closed-form absolute orientation (see absolute_orientation.h).
#include "trackbed/estimation/absolute_orientation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

namespace trackbed::estimation {

Eigen::Isometry3d SimilarityTransform::Rigid() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t;
  return T;
}

namespace {

struct HornSolution {
  SimilarityTransform transform;
  int pairs = 0;        // pairs with positive weight
  bool unique = false;  // the rotation is the only minimiser
};

void CheckArguments(const char* function, const std::vector<Eigen::Vector3d>& src,
                    const std::vector<Eigen::Vector3d>& dst, const std::vector<double>& weights) {
  const std::string f = function;
  if (src.size() != dst.size()) {
    throw std::invalid_argument(f + ": src has " + std::to_string(src.size()) +
                                " points but dst has " + std::to_string(dst.size()));
  }
  if (!weights.empty() && weights.size() != src.size()) {
    throw std::invalid_argument(f + ": " + std::to_string(weights.size()) + " weights for " +
                                std::to_string(src.size()) + " point pairs");
  }
  for (std::size_t i = 0; i < weights.size(); ++i) {
    if (!(std::isfinite(weights[i]) && weights[i] >= 0.0)) {
      throw std::invalid_argument(f + ": weight " + std::to_string(i) +
                                  " must be finite and >= 0 (got " + std::to_string(weights[i]) +
                                  ")");
    }
  }
  for (std::size_t i = 0; i < src.size(); ++i) {
    if (!src[i].allFinite() || !dst[i].allFinite()) {
      throw std::invalid_argument(f + ": point pair " + std::to_string(i) + " is not finite");
    }
  }
}

void SolveFromMoments(const Eigen::Vector3d& c_src, const Eigen::Vector3d& c_dst,
                      const Eigen::Matrix3d& S, double spread_src, double spread_dst,
                      bool with_scale, HornSolution* out_solution);

HornSolution Solve(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst,
                   bool with_scale, const std::vector<double>& weights) {
  HornSolution out;
  const std::size_t n = src.size();
  auto w = [&](std::size_t i) { return weights.empty() ? 1.0 : weights[i]; };

  // Weighted centroids.
  double w_sum = 0.0;
  Eigen::Vector3d c_src = Eigen::Vector3d::Zero(), c_dst = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (w(i) <= 0.0) continue;
    ++out.pairs;
    w_sum += w(i);
    c_src += w(i) * src[i];
    c_dst += w(i) * dst[i];
  }
  if (out.pairs == 0) return out;
  c_src /= w_sum;
  c_dst /= w_sum;

  // Cross-covariance S = Σ w src' dst'ᵀ of the centred points (Horn's M, entries S_xy…),
  // and the weighted spreads Σ w |src'|², Σ w |dst'|².
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  double spread_src = 0.0, spread_dst = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (w(i) <= 0.0) continue;
    const Eigen::Vector3d a = src[i] - c_src, b = dst[i] - c_dst;
    S += w(i) * a * b.transpose();
    spread_src += w(i) * a.squaredNorm();
    spread_dst += w(i) * b.squaredNorm();
  }

  SolveFromMoments(c_src, c_dst, S, spread_src, spread_dst, with_scale, &out);
  return out;
}

// Horn's rotation (and the scale and translation) from the centroids, the cross-covariance
// S = Σ w src' dst'ᵀ of the centred points and their spreads; out->pairs is already set.
void SolveFromMoments(const Eigen::Vector3d& c_src, const Eigen::Vector3d& c_dst,
                      const Eigen::Matrix3d& S, double spread_src, double spread_dst,
                      bool with_scale, HornSolution* out_solution) {
  HornSolution& out = *out_solution;
  // Horn's symmetric 4×4 matrix N (1987, §4): for a unit quaternion q = (q0, qx, qy, qz),
  // qᵀ N q = Σ w b'·(R(q) a'), so the maximiser is N's eigenvector of the largest eigenvalue.
  const double Sxx = S(0, 0), Sxy = S(0, 1), Sxz = S(0, 2);
  const double Syx = S(1, 0), Syy = S(1, 1), Syz = S(1, 2);
  const double Szx = S(2, 0), Szy = S(2, 1), Szz = S(2, 2);
  Eigen::Matrix4d N;
  N << Sxx + Syy + Szz, Syz - Szy, Szx - Sxz, Sxy - Syx,  //
      Syz - Szy, Sxx - Syy - Szz, Sxy + Syx, Szx + Sxz,   //
      Szx - Sxz, Sxy + Syx, -Sxx + Syy - Szz, Syz + Szy,  //
      Sxy - Syx, Szx + Sxz, Syz + Szy, -Sxx - Syy + Szz;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(N);
  if (eig.info() != Eigen::Success) {
    throw std::logic_error("HornAbsoluteOrientation: eigen-decomposition of N failed");
  }
  // Eigenvalues ascending: λ_max = [3]. Its eigenvector is unique iff λ_max > λ_2; the gap
  // is 2(σ2 ± σ3) in the singular values of S, zero for collinear or coincident points.
  const double lambda_max = eig.eigenvalues()(3);
  const double gap = lambda_max - eig.eigenvalues()(2);
  const double magnitude = std::sqrt(spread_src * spread_dst);
  out.unique = out.pairs >= 3 && magnitude > 0.0 && gap > 1e-10 * magnitude;

  Eigen::Vector4d q = eig.eigenvectors().col(3);
  if (q(0) < 0.0) q = -q;  // one sign for determinism; ±q is the same rotation
  const Eigen::Quaterniond quat(q(0), q(1), q(2), q(3));
  SimilarityTransform& T = out.transform;
  T.R = quat.normalized().toRotationMatrix();
  // Umeyama's least-squares scale: Σ w b'·(R a') / Σ w |a'|², and λ_max = Σ w b'·(R a').
  T.scale = (with_scale && spread_src > 0.0) ? std::max(lambda_max, 0.0) / spread_src : 1.0;
  T.t = c_dst - T.scale * (T.R * c_src);
}

}  // namespace

std::optional<SimilarityTransform> HornAbsoluteOrientation(const std::vector<Eigen::Vector3d>& src,
                                                           const std::vector<Eigen::Vector3d>& dst,
                                                           bool with_scale,
                                                           const std::vector<double>& weights) {
  CheckArguments("HornAbsoluteOrientation", src, dst, weights);
  const HornSolution s = Solve(src, dst, with_scale, weights);
  if (s.pairs < 3 || !s.unique) return std::nullopt;
  return s.transform;
}

SimilarityTransform HornAbsoluteOrientationAnyMinimizer(const std::vector<Eigen::Vector3d>& src,
                                                        const std::vector<Eigen::Vector3d>& dst,
                                                        bool with_scale,
                                                        const std::vector<double>& weights,
                                                        bool* unique) {
  CheckArguments("HornAbsoluteOrientationAnyMinimizer", src, dst, weights);
  const HornSolution s = Solve(src, dst, with_scale, weights);
  if (s.pairs == 0) {
    throw std::invalid_argument(
        "HornAbsoluteOrientationAnyMinimizer: no point pair with positive weight");
  }
  if (unique) *unique = s.unique;
  return s.transform;
}

void PointPairMoments::Add(const Eigen::Vector3d& src, const Eigen::Vector3d& dst) {
  ++count;
  const double n = static_cast<double>(count);
  const Eigen::Vector3d d_src = src - mean_src, d_dst = dst - mean_dst;  // from the old means
  mean_src += d_src / n;
  mean_dst += d_dst / n;
  // Co-moment updates: (x − x̄ₙ₋₁)(y − ȳₙ) sums to Σ (x − x̄)(y − ȳ) exactly in exact arithmetic.
  const Eigen::Vector3d e_dst = dst - mean_dst;
  S += d_src * e_dst.transpose();
  spread_src += d_src.dot(src - mean_src);
  spread_dst += d_dst.dot(e_dst);
}

double PointPairMoments::ResidualSquaredSum(const SimilarityTransform& T) const {
  const double r = spread_dst - 2.0 * T.scale * (T.R * S).trace() + T.scale * T.scale * spread_src;
  return std::max(r, 0.0);
}

SimilarityTransform HornAbsoluteOrientationFromMoments(const PointPairMoments& moments,
                                                       bool with_scale, bool* unique) {
  if (moments.count < 1) {
    throw std::invalid_argument("HornAbsoluteOrientationFromMoments: needs at least one pair");
  }
  HornSolution s;
  s.pairs = static_cast<int>(std::min<long long>(moments.count, std::numeric_limits<int>::max()));
  SolveFromMoments(moments.mean_src, moments.mean_dst, moments.S, moments.spread_src,
                   moments.spread_dst, with_scale, &s);
  if (unique) *unique = s.unique;
  return s.transform;
}

}  // namespace trackbed::estimation
