// Closed-form absolute orientation: the rigid or similarity transform that best maps
// one set of 3-D points onto another (Horn, "Closed-form solution of absolute
// orientation using unit quaternions", J. Opt. Soc. Am. A 4(4), 1987).
//
// Used by visual odometry (the motion from inlier 3D–3D correspondences, Ham et al.
// 2012 §3.2) and by the trajectory metrics (SE(3)/Sim(3) alignment before the ATE).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace trackbed::estimation {

/// A similarity transform x ↦ s·R·x + t.
struct SimilarityTransform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< rotation, det R = +1
  Eigen::Vector3d t = Eigen::Vector3d::Zero();      ///< translation [m]
  double scale = 1.0;                               ///< s (1 for a rigid transform)

  Eigen::Vector3d Apply(const Eigen::Vector3d& x) const { return scale * (R * x) + t; }
  Eigen::Isometry3d Rigid() const;  ///< R, t (ignores scale)
};

/// Horn (1987) closed-form absolute orientation with unit quaternions: the R (and t, and
/// s when with_scale) minimising Σ w_i |dst_i − (s R src_i + t)|² (weights optional:
/// empty = all 1).
///
/// R is the rotation of the unit quaternion that is the eigenvector of Horn's symmetric
/// 4×4 matrix N (built from the weighted cross-covariance of the centred points) for its
/// largest eigenvalue λ_max; it is always a proper rotation (det R = +1), also when the
/// best orthogonal fit of noisy data would be a reflection. The scale is Umeyama's
/// (1991) least-squares scale s = λ_max / Σ w_i |src_i − c_src|², the one that minimises
/// the cost above — NOT Horn's symmetric scale sqrt(Σ w|dst'|² / Σ w|src'|²), which
/// minimises a different (symmetrised) cost. With it the result equals Eigen::umeyama's.
/// t = c_dst − s R c_src (weighted centroids).
///
/// Returns std::nullopt for fewer than 3 pairs with positive weight or a degenerate
/// configuration, where the rotation is not unique: all points collinear or coincident
/// in src or in dst (numerically: the gap between N's two largest eigenvalues is below
/// 1e-10 of the points' scale). Throws std::invalid_argument if src and dst differ in
/// size, weights is neither empty nor of that size, or a weight is negative or not
/// finite.
std::optional<SimilarityTransform> HornAbsoluteOrientation(const std::vector<Eigen::Vector3d>& src,
                                                           const std::vector<Eigen::Vector3d>& dst,
                                                           bool with_scale = false,
                                                           const std::vector<double>& weights = {});

/// Horn's solution without the uniqueness check, for callers that only need *a*
/// minimiser (e.g. trajectory alignment, where a straight-line run is collinear and any
/// rotation about that line gives the same, minimal error). For a degenerate
/// configuration it returns one of the equally optimal transforms (deterministically);
/// `unique`, if given, is set to false in that case. Needs at least one pair with
/// positive weight (else std::invalid_argument), and the same argument checks as above.
/// With all src points coincident the scale is 1; with all dst points coincident, 0.
SimilarityTransform HornAbsoluteOrientationAnyMinimizer(const std::vector<Eigen::Vector3d>& src,
                                                        const std::vector<Eigen::Vector3d>& dst,
                                                        bool with_scale = false,
                                                        const std::vector<double>& weights = {},
                                                        bool* unique = nullptr);

/// The moments of a growing set of point pairs (src_i, dst_i), all of weight 1, from which
/// Horn's solution is exact without keeping the points: the count, both centroids, the
/// cross-covariance S = Σ src' dst'ᵀ of the centred points and their spreads Σ |src'|²,
/// Σ |dst'|². Accumulated with Welford's centred updates (Welford 1962; the co-moment form
/// of Chan, Golub & LeVeque 1983), so that a trajectory far from the origin loses no digits.
struct PointPairMoments {
  long long count = 0;
  Eigen::Vector3d mean_src = Eigen::Vector3d::Zero(), mean_dst = Eigen::Vector3d::Zero();
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();  ///< Σ (src − mean_src)(dst − mean_dst)ᵀ
  double spread_src = 0.0, spread_dst = 0.0;  ///< Σ |src − mean_src|², Σ |dst − mean_dst|²

  void Add(const Eigen::Vector3d& src, const Eigen::Vector3d& dst);
  /// Σ |dst_i − (s R src_i + t)|² for a transform whose t = mean_dst − s R mean_src (the
  /// minimiser's): Σ|dst'|² − 2 s tr(R S) + s² Σ|src'|², clamped at 0.
  double ResidualSquaredSum(const SimilarityTransform& T) const;
};

/// HornAbsoluteOrientationAnyMinimizer from accumulated moments: the same transform up to
/// floating-point rounding (the moments are summed in another order). Needs count ≥ 1 (else
/// std::invalid_argument).
SimilarityTransform HornAbsoluteOrientationFromMoments(const PointPairMoments& moments,
                                                       bool with_scale = false,
                                                       bool* unique = nullptr);

}  // namespace trackbed::estimation
