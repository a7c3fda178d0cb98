// The motion of a stereo pair between two frames: RANSAC with Horn's absolute
// orientation, reprojection refinement, and the two combined (see
// stereo_motion_estimation.h).
#include "trackbed/estimation/stereo_motion_estimation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>

#include "trackbed/common/option_error.h"
#include "trackbed/common/se3.h"
#include "trackbed/estimation/absolute_orientation.h"

namespace trackbed::estimation {
namespace {

/// Huber cost of a residual norm e with threshold k: e² inside, 2ke − k² outside.
double Huber(double e, double k) { return e <= k ? e * e : 2.0 * k * e - k * k; }

/// Cost of the masked correspondences under T (points behind the camera count as a
/// large constant, so a step that pushes points behind is not preferred).
double RobustCost(const std::vector<MotionCorrespondence>& c, const std::vector<int>& active,
                  const geometry::StereoCamera& camera, const Eigen::Isometry3d& T, double k,
                  double* sum_sq) {
  double cost = 0.0, sq = 0.0;
  for (int i : active) {
    const Eigen::Vector3d p = T * c[static_cast<std::size_t>(i)].p_prev;
    if (!(p.z() > 1e-6)) {
      cost += 1e6;
      continue;
    }
    const Eigen::Vector3d r = camera.Project(p) - c[static_cast<std::size_t>(i)].z_curr;
    sq += r.squaredNorm();
    cost += Huber(r.norm(), k);
  }
  if (sum_sq) *sum_sq = sq;
  return cost;
}

int CountInliers(const std::vector<MotionCorrespondence>& c, const geometry::StereoCamera& camera,
                 const Eigen::Isometry3d& T, double threshold_px,
                 std::vector<unsigned char>* mask) {
  int count = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const bool in = IsReprojectionInlier(camera, T, c[i], threshold_px);
    if (mask) (*mask)[i] = in ? 1 : 0;
    count += in ? 1 : 0;
  }
  return count;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Camera model and residuals.

Eigen::Isometry3d ApplyIncrement(const MotionIncrement& delta, const Eigen::Isometry3d& T) {
  return geometry::ApplyLeftIncrement(delta.head<3>(), delta.tail<3>(), T);
}

Eigen::Vector3d StereoReprojectionResidual(const geometry::StereoCamera& camera,
                                           const Eigen::Isometry3d& T_curr_prev,
                                           const MotionCorrespondence& c,
                                           Eigen::Matrix<double, 3, 6>* J) {
  const Eigen::Vector3d p = T_curr_prev * c.p_prev;
  const Eigen::Vector3d r = camera.Project(p) - c.z_curr;
  if (J) {
    // ∂(u_l, v, u_r)/∂p for u = fx·X/Z + cx, v = fy·Y/Z + cy, u_r = fx·(X − b)/Z + cx,
    // times ∂p/∂δ = [I | −[p]×] (left increment: p ← Exp(φ)p + ρ ≈ p + ρ + φ × p).
    const double iz = 1.0 / p.z(), iz2 = iz * iz;
    Eigen::Matrix3d P;
    P << camera.left.fx * iz, 0.0, -camera.left.fx * p.x() * iz2,  //
        0.0, camera.left.fy * iz, -camera.left.fy * p.y() * iz2,   //
        camera.left.fx * iz, 0.0, -camera.left.fx * (p.x() - camera.baseline_m) * iz2;
    J->leftCols<3>() = P;
    J->rightCols<3>() = -P * geometry::Skew(p);
  }
  return r;
}

bool IsReprojectionInlier(const geometry::StereoCamera& camera,
                          const Eigen::Isometry3d& T_curr_prev, const MotionCorrespondence& c,
                          double threshold_px) {
  const Eigen::Vector3d p = T_curr_prev * c.p_prev;
  if (!(p.z() > 1e-6)) return false;
  const Eigen::Vector3d r = camera.Project(p) - c.z_curr;
  const double t2 = threshold_px * threshold_px;
  const double v2 = r.y() * r.y();
  return r.x() * r.x() + v2 <= t2 && r.z() * r.z() + v2 <= t2;
}

// ---------------------------------------------------------------------------------------
// RANSAC.

void MotionRansacOptions::Validate() const {
  if (max_iterations < 1) {
    throw OptionError("max_iterations",
                      "must be >= 1 (got " + std::to_string(max_iterations) + ")");
  }
  if (!(std::isfinite(confidence) && confidence > 0.0 && confidence < 1.0)) {
    throw OptionError("confidence",
                      "must be in (0, 1) (got " + option_check::Describe(confidence) + ")");
  }
  option_check::Positive("threshold_px", threshold_px);
}

namespace {

/// Three distinct indices drawn uniformly (a repeat is drawn again).
void DrawSample(std::size_t n, random::Generator& rng, std::size_t s[3]) {
  s[0] = rng.UniformIndex(n);
  do s[1] = rng.UniformIndex(n);
  while (s[1] == s[0]);
  do s[2] = rng.UniformIndex(n);
  while (s[2] == s[0] || s[2] == s[1]);
}

/// Adaptive stop (Fischler & Bolles 1981; Hartley & Zisserman §4.7.1): how many
/// hypotheses to draw in all, at most `needed`, once the best one after hypothesis
/// `it` (from 0) has `count` of n inliers. log_failure = log(1 − confidence).
int HypothesesNeeded(int count, std::size_t n, double log_failure, int it, int needed) {
  const double ratio = static_cast<double>(count) / static_cast<double>(n);
  const double p_good = ratio * ratio * ratio;
  if (p_good >= 1.0) return it + 1;
  if (p_good > 0.0) {
    const double k = log_failure / std::log(1.0 - p_good);
    if (k < static_cast<double>(needed)) return static_cast<int>(std::ceil(k));
  }
  return needed;
}

/// Refits result's motion on its inliers (>= 3) and keeps the refit unless it has fewer
/// inliers. Stereo depth noise dominates the 3-D error and grows as Z²
/// (σ_Z = Z²σ_d/(fx·b)), so each pair is weighted by the inverse variance of the
/// difference of its two depths, 1/(Z_prev⁴ + Z_curr⁴) (up to a constant).
void RefitOnInliers(const std::vector<MotionCorrespondence>& correspondences,
                    const geometry::StereoCamera& camera, double threshold_px,
                    MotionRansacResult* result) {
  std::vector<Eigen::Vector3d> src, dst;
  std::vector<double> weights;
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    if (!result->inlier_mask[i]) continue;
    src.push_back(correspondences[i].p_prev);
    dst.push_back(correspondences[i].p_curr);
    const double z0 = correspondences[i].p_prev.z(), z1 = correspondences[i].p_curr.z();
    weights.push_back(1.0 / (z0 * z0 * z0 * z0 + z1 * z1 * z1 * z1));
  }
  if (const auto refit = HornAbsoluteOrientation(src, dst, false, weights)) {
    const Eigen::Isometry3d T = refit->Rigid();
    const int count = CountInliers(correspondences, camera, T, threshold_px, nullptr);
    if (count >= result->inliers) {
      result->T_curr_prev = T;
      result->inliers =
          CountInliers(correspondences, camera, T, threshold_px, &result->inlier_mask);
    }
  }
}

}  // namespace

void EstimateMotionRansac(const std::vector<MotionCorrespondence>& correspondences,
                          const geometry::StereoCamera& camera, const MotionRansacOptions& options,
                          random::Generator& rng, MotionRansacResult* result) {
  options.Validate();
  const std::size_t n = correspondences.size();
  result->success = false;
  result->T_curr_prev = Eigen::Isometry3d::Identity();
  result->inliers = 0;
  result->iterations = 0;
  result->inlier_mask.assign(n, 0);
  if (n < 3) return;

  std::vector<Eigen::Vector3d> src(3), dst(3);
  int best = -1;
  Eigen::Isometry3d best_T = Eigen::Isometry3d::Identity();
  int needed = options.max_iterations;
  const double log_failure = std::log(1.0 - options.confidence);
  for (int it = 0; it < needed; ++it) {
    ++result->iterations;
    std::size_t s[3];
    DrawSample(n, rng, s);
    for (int k = 0; k < 3; ++k) {
      src[static_cast<std::size_t>(k)] = correspondences[s[k]].p_prev;
      dst[static_cast<std::size_t>(k)] = correspondences[s[k]].p_curr;
    }
    const std::optional<SimilarityTransform> horn = HornAbsoluteOrientation(src, dst);
    if (!horn) continue;  // collinear sample
    const Eigen::Isometry3d T = horn->Rigid();
    const int count = CountInliers(correspondences, camera, T, options.threshold_px, nullptr);
    if (count > best) {
      best = count;
      best_T = T;
      needed = HypothesesNeeded(count, n, log_failure, it, needed);
    }
  }
  if (best < 0) return;
  result->success = true;
  result->T_curr_prev = best_T;
  result->inliers =
      CountInliers(correspondences, camera, best_T, options.threshold_px, &result->inlier_mask);
  if (result->inliers >= 3) RefitOnInliers(correspondences, camera, options.threshold_px, result);
}

// ---------------------------------------------------------------------------------------
// Reprojection refinement.

void MotionRefinementOptions::Validate() const {
  if (max_iterations < 0) {
    throw OptionError("max_iterations",
                      "must be >= 0 (got " + std::to_string(max_iterations) + ")");
  }
  option_check::Positive("huber_px", huber_px);
  option_check::Positive("min_step", min_step);
}

namespace {

/// Normal equations H δ = −g of the IRLS-weighted (Huber) Gauss–Newton step at T over
/// the active correspondences: weight 1 for a residual norm e <= k [px], k/e beyond;
/// points behind the camera are skipped.
void HuberNormalEquations(const std::vector<MotionCorrespondence>& correspondences,
                          const std::vector<int>& active, const geometry::StereoCamera& camera,
                          const Eigen::Isometry3d& T, double k, Eigen::Matrix<double, 6, 6>* H,
                          MotionIncrement* g) {
  H->setZero();
  g->setZero();
  Eigen::Matrix<double, 3, 6> J;
  for (int i : active) {
    const MotionCorrespondence& c = correspondences[static_cast<std::size_t>(i)];
    if (!((T * c.p_prev).z() > 1e-6)) continue;
    const Eigen::Vector3d r = StereoReprojectionResidual(camera, T, c, &J);
    const double e = r.norm();
    const double w = e <= k ? 1.0 : k / e;
    H->noalias() += w * J.transpose() * J;
    g->noalias() += w * J.transpose() * r;
  }
}

/// One Levenberg–Marquardt step: damps H (adds λ times its diagonal), λ growing tenfold,
/// until the step lowers the robust cost, then takes it (*T, *cost, *sum_sq) and relaxes
/// λ. False when no damping up to λ = 1e8 lowers the cost. *delta is the last step tried.
bool DampedStep(const Eigen::Matrix<double, 6, 6>& H, const MotionIncrement& g,
                const std::vector<MotionCorrespondence>& correspondences,
                const std::vector<int>& active, const geometry::StereoCamera& camera, double k,
                double* lambda, MotionIncrement* delta, Eigen::Isometry3d* T, double* cost,
                double* sum_sq) {
  while (*lambda < 1e8) {
    Eigen::Matrix<double, 6, 6> A = H;
    A.diagonal() += *lambda * H.diagonal().cwiseMax(1e-12);
    *delta = A.ldlt().solve(-g);
    if (!delta->allFinite()) {
      *lambda *= 10.0;
      continue;
    }
    const Eigen::Isometry3d T_new = ApplyIncrement(*delta, *T);
    double sq_new = 0.0;
    const double cost_new = RobustCost(correspondences, active, camera, T_new, k, &sq_new);
    if (cost_new <= *cost) {
      *T = T_new;
      *cost = cost_new;
      *sum_sq = sq_new;
      *lambda = std::max(*lambda * 0.1, 1e-9);
      return true;
    }
    *lambda *= 10.0;
  }
  return false;
}

}  // namespace

MotionRefinementResult RefineMotionReprojection(
    const std::vector<MotionCorrespondence>& correspondences,
    const std::vector<unsigned char>& mask, const geometry::StereoCamera& camera,
    const Eigen::Isometry3d& T_init, const MotionRefinementOptions& options) {
  options.Validate();
  if (!mask.empty() && mask.size() != correspondences.size()) {
    throw std::invalid_argument("RefineMotionReprojection: mask has " +
                                std::to_string(mask.size()) + " entries for " +
                                std::to_string(correspondences.size()) + " correspondences");
  }
  std::vector<int> active;
  active.reserve(correspondences.size());
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    if (mask.empty() || mask[i]) active.push_back(static_cast<int>(i));
  }
  MotionRefinementResult out;
  out.T_curr_prev = T_init;
  if (active.empty()) {
    out.converged = true;
    return out;
  }
  const double k = options.huber_px;
  const double norm = 1.0 / (3.0 * static_cast<double>(active.size()));
  double sum_sq = 0.0;
  double cost = RobustCost(correspondences, active, camera, out.T_curr_prev, k, &sum_sq);
  out.initial_rms_px = std::sqrt(sum_sq * norm);
  out.final_rms_px = out.initial_rms_px;

  double lambda = 1e-6;
  Eigen::Matrix<double, 6, 6> H;
  MotionIncrement g;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    HuberNormalEquations(correspondences, active, camera, out.T_curr_prev, k, &H, &g);
    ++out.iterations;
    MotionIncrement delta = MotionIncrement::Zero();
    const bool accepted = DampedStep(H, g, correspondences, active, camera, k, &lambda, &delta,
                                     &out.T_curr_prev, &cost, &sum_sq);
    if (!accepted || delta.norm() < options.min_step) {
      out.converged = true;  // no step lowers the cost, or the step is negligible
      break;
    }
  }
  out.final_rms_px = std::sqrt(sum_sq * norm);
  return out;
}

DisparityOffsetMeasurement MeasureDisparityOffset(
    const std::vector<MotionCorrespondence>& correspondences,
    const std::vector<unsigned char>& mask, const geometry::StereoCamera& camera,
    const Eigen::Isometry3d& T_curr_prev, double huber_px) {
  Eigen::Matrix<double, 7, 7> H = Eigen::Matrix<double, 7, 7>::Zero();
  Eigen::Matrix<double, 7, 1> g = Eigen::Matrix<double, 7, 1>::Zero();
  double sum_sq = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const MotionCorrespondence& c = correspondences[i];
    Eigen::Matrix<double, 3, 6> Jm;
    const Eigen::Vector3d r = StereoReprojectionResidual(camera, T_curr_prev, c, &Jm);
    const double d_prev = c.z_prev.x() - c.z_prev.z();
    if (!(d_prev > 0.0)) continue;
    // p_prev(δ) = Triangulate(u, v, d + δ): ∂p_prev/∂δ = −p_prev / d, moved by T's
    // rotation; ∂r/∂p is the Jacobian's translation block. The measured right
    // coordinate carries −δ: r_right gains +δ.
    Eigen::Matrix<double, 3, 7> J;
    J.leftCols<6>() = Jm;
    const Eigen::Vector3d dp = -(T_curr_prev.linear() * c.p_prev) / d_prev;
    J.col(6) = Jm.leftCols<3>() * dp + Eigen::Vector3d(0.0, 0.0, 1.0);
    const double e = r.norm();
    const double w = e <= huber_px ? 1.0 : huber_px / e;
    H.noalias() += w * J.transpose() * J;
    g.noalias() += w * J.transpose() * r;
    sum_sq += r.squaredNorm();
    ++n;
  }
  DisparityOffsetMeasurement out;
  if (n < kMinDisparityOffsetPoints) return out;
  const Eigen::Matrix<double, 6, 6> Hmm = H.topLeftCorner<6, 6>();
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(Hmm);
  const Eigen::Matrix<double, 6, 1> Hmd = H.block<6, 1>(0, 6);
  const double info = H(6, 6) - Hmd.dot(ldlt.solve(Hmd));
  const double grad = g(6) - Hmd.dot(ldlt.solve(g.head<6>()));
  if (!(info > 1e-9)) return out;
  const double sigma2 = sum_sq / (3.0 * n);
  out.valid = true;
  out.information = info;
  out.offset_px = -grad / info;
  out.variance_px2 = sigma2 / info;
  return out;
}

// ---------------------------------------------------------------------------------------
// RANSAC and refinement combined.

void StereoMotionOptions::Validate() const {
  option_check::Nested("ransac", ransac);
  option_check::Nested("refinement", refinement);
  if (min_inliers < 3) {
    throw OptionError("min_inliers", "must be >= 3 (got " + std::to_string(min_inliers) + ")");
  }
}

const char* ToString(StereoMotionStatus status) {
  switch (status) {
    case StereoMotionStatus::kOk:
      return "ok";
    case StereoMotionStatus::kTooFewCorrespondences:
      return "too_few_correspondences";
    case StereoMotionStatus::kDegenerate:
      return "degenerate";
    case StereoMotionStatus::kTooFewConsensusInliers:
      return "too_few_consensus_inliers";
    case StereoMotionStatus::kTooFewRefinedInliers:
      return "too_few_refined_inliers";
  }
  return "unknown";
}

namespace {

/// RANSAC on the correspondences whose `candidates` entry is non-zero, its inlier mask
/// spread back over all correspondences (0 for the others).
void RansacOnCandidates(const std::vector<MotionCorrespondence>& correspondences,
                        const std::vector<unsigned char>& candidates,
                        const geometry::StereoCamera& camera, const MotionRansacOptions& options,
                        random::Generator& rng, MotionRansacResult* result) {
  std::vector<MotionCorrespondence> subset;
  std::vector<std::size_t> index;  // subset → correspondences
  for (std::size_t j = 0; j < correspondences.size(); ++j) {
    if (!candidates[j]) continue;
    subset.push_back(correspondences[j]);
    index.push_back(j);
  }
  EstimateMotionRansac(subset, camera, options, rng, result);
  std::vector<unsigned char> subset_mask;
  subset_mask.swap(result->inlier_mask);
  result->inlier_mask.assign(correspondences.size(), 0);
  for (std::size_t k = 0; k < subset.size(); ++k) result->inlier_mask[index[k]] = subset_mask[k];
}

/// Refines T_init on the correspondences `mask` selects, re-selects the inliers among all
/// correspondences, and, if min_inliers remain, refines on them and re-selects once
/// more: a consensus's inliers are those of a 3-point hypothesis (or of a refit on
/// them), the refined motion may keep others. Sets result's inlier_mask, inliers and
/// refinement (its motion with the rotation re-orthonormalised); `mask` must not be
/// result->inlier_mask.
void RefineAndReselect(const std::vector<MotionCorrespondence>& correspondences,
                       const std::vector<unsigned char>& mask, const geometry::StereoCamera& camera,
                       const Eigen::Isometry3d& T_init, const StereoMotionOptions& options,
                       StereoMotionResult* result) {
  const double threshold = options.ransac.threshold_px;
  result->inlier_mask.resize(correspondences.size());
  MotionRefinementResult refined =
      RefineMotionReprojection(correspondences, mask, camera, T_init, options.refinement);
  result->inliers =
      CountInliers(correspondences, camera, refined.T_curr_prev, threshold, &result->inlier_mask);
  if (result->inliers >= options.min_inliers) {
    refined = RefineMotionReprojection(correspondences, result->inlier_mask, camera,
                                       refined.T_curr_prev, options.refinement);
    result->inliers =
        CountInliers(correspondences, camera, refined.T_curr_prev, threshold, &result->inlier_mask);
  }
  // LM composes rotations step by step; keep the result a rotation to the last bit.
  refined.T_curr_prev.linear() =
      Eigen::Quaterniond(refined.T_curr_prev.linear()).normalized().toRotationMatrix();
  result->refinement = refined;
}

}  // namespace

void EstimateStereoMotion(const std::vector<MotionCorrespondence>& correspondences,
                          const std::vector<unsigned char>& candidates,
                          const geometry::StereoCamera& camera, const StereoMotionOptions& options,
                          random::Generator& rng, StereoMotionResult* result) {
  options.Validate();
  const std::size_t n = correspondences.size();
  if (!candidates.empty() && candidates.size() != n) {
    throw std::invalid_argument("EstimateStereoMotion: candidates mask has " +
                                std::to_string(candidates.size()) + " entries for " +
                                std::to_string(n) + " correspondences");
  }
  result->status = StereoMotionStatus::kTooFewCorrespondences;
  result->T_curr_prev = Eigen::Isometry3d::Identity();
  result->inlier_mask.clear();
  result->inliers = 0;
  result->candidates = candidates.empty()
                           ? static_cast<int>(n)
                           : static_cast<int>(std::count_if(candidates.begin(), candidates.end(),
                                                            [](unsigned char c) { return c; }));
  result->ransac.success = false;
  result->ransac.T_curr_prev = Eigen::Isometry3d::Identity();
  result->ransac.inliers = 0;
  result->ransac.iterations = 0;
  result->ransac.inlier_mask.clear();
  result->refinement = MotionRefinementResult{};
  if (result->candidates < options.min_inliers) return;

  // 1. RANSAC's consensus.
  if (candidates.empty()) {
    EstimateMotionRansac(correspondences, camera, options.ransac, rng, &result->ransac);
  } else {
    RansacOnCandidates(correspondences, candidates, camera, options.ransac, rng, &result->ransac);
  }
  if (!result->ransac.success) {
    result->status = StereoMotionStatus::kDegenerate;
    return;
  }
  if (result->ransac.inliers < options.min_inliers) {
    result->status = StereoMotionStatus::kTooFewConsensusInliers;
    return;
  }

  // 2. Refinement from the consensus, with re-selected inliers.
  RefineAndReselect(correspondences, result->ransac.inlier_mask, camera, result->ransac.T_curr_prev,
                    options, result);
  if (result->inliers < options.min_inliers ||
      !result->refinement.T_curr_prev.matrix().allFinite()) {
    result->status = StereoMotionStatus::kTooFewRefinedInliers;
    return;
  }
  result->status = StereoMotionStatus::kOk;
  result->T_curr_prev = result->refinement.T_curr_prev;
}

}  // namespace trackbed::estimation
