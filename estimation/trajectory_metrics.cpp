// Trajectory metrics (see trajectory_metrics.h).
#include "trackbed/estimation/trajectory_metrics.h"

#include "trackbed/estimation/per_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "trackbed/common/option_error.h"

namespace trackbed::estimation {

namespace {

constexpr double kPi = 3.14159265358979323846;

void CheckAssociated(const char* function, const Trajectory& gt, const Trajectory& est) {
  if (gt.size() != est.size()) {
    throw std::invalid_argument(std::string(function) + ": " + std::to_string(gt.size()) +
                                " ground-truth poses but " + std::to_string(est.size()) +
                                " estimated poses (associate them first)");
  }
  if (gt.empty()) throw std::invalid_argument(std::string(function) + ": no poses");
}

// Relative motion from pose a to pose b, A⁻¹B, with a general 4×4 inverse as the KITTI devkit
// does: KITTI files round rotations to 7 digits, and the transpose of such an R is not its
// inverse, which would bias small rotation angles upward (acos near 1 amplifies it).
Eigen::Matrix4d Relative(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return a.matrix().inverse() * b.matrix();
}

// E = (Q_i⁻¹ Q_j)⁻¹ (P_i⁻¹ P_j).
Eigen::Matrix4d RelativeError(const Trajectory& gt, const Trajectory& est, std::size_t i,
                              std::size_t j) {
  return Relative(gt[i].T_world_body, gt[j].T_world_body).inverse() *
         Relative(est[i].T_world_body, est[j].T_world_body);
}

// The KITTI devkit's rotation angle [rad]: acos(clamp((tr R − 1)/2, −1, 1)).
double DevkitAngle(const Eigen::Matrix4d& E) {
  const double d = 0.5 * (E(0, 0) + E(1, 1) + E(2, 2) - 1.0);
  return std::acos(std::max(std::min(d, 1.0), -1.0));
}

// Rotation angle [rad] accurate also near 0: atan2(|axis part|, cos part).
double Angle(const Eigen::Matrix4d& E) {
  const Eigen::Vector3d v(E(2, 1) - E(1, 2), E(0, 2) - E(2, 0), E(1, 0) - E(0, 1));
  return std::atan2(0.5 * v.norm(), 0.5 * (E(0, 0) + E(1, 1) + E(2, 2) - 1.0));
}

// Cumulative ground-truth path length [m] at each pose.
std::vector<double> CumulativeDistance(const Trajectory& gt) {
  std::vector<double> d(gt.size(), 0.0);
  for (std::size_t k = 1; k < gt.size(); ++k) {
    d[k] =
        d[k - 1] + (gt[k].T_world_body.translation() - gt[k - 1].T_world_body.translation()).norm();
  }
  return d;
}

Eigen::Vector3d Position(const StampedPose& p, bool horizontal) {
  Eigen::Vector3d v = p.T_world_body.translation();
  if (horizontal) v.z() = 0.0;
  return v;
}

}  // namespace

// ---------------------------------------------------------------------------------------

const char* AlignmentModeName(AlignmentMode mode) {
  switch (mode) {
    case AlignmentMode::kNone:
      return "none";
    case AlignmentMode::kSe3:
      return "se3";
    case AlignmentMode::kSim3:
      return "sim3";
  }
  return "?";
}

AlignmentMode ParseAlignmentMode(const std::string& name) {
  for (AlignmentMode m : {AlignmentMode::kNone, AlignmentMode::kSe3, AlignmentMode::kSim3}) {
    if (name == AlignmentModeName(m)) return m;
  }
  throw std::invalid_argument("unknown alignment '" + name + "' (expected none, se3 or sim3)");
}

Alignment Align(const Trajectory& gt, const Trajectory& est, AlignmentMode mode) {
  CheckAssociated("Align", gt, est);
  Alignment out;
  out.mode = mode;
  if (mode == AlignmentMode::kNone) return out;
  std::vector<Eigen::Vector3d> p_est, p_gt;
  p_est.reserve(est.size());
  p_gt.reserve(gt.size());
  for (std::size_t k = 0; k < gt.size(); ++k) {
    p_est.push_back(est[k].T_world_body.translation());
    p_gt.push_back(gt[k].T_world_body.translation());
  }
  out.T_gt_est = HornAbsoluteOrientationAnyMinimizer(p_est, p_gt, mode == AlignmentMode::kSim3, {},
                                                     &out.unique);
  return out;
}

Trajectory ApplyAlignment(const SimilarityTransform& T, const Trajectory& est) {
  Trajectory out = est;
  for (StampedPose& p : out) {
    const Eigen::Vector3d position = T.Apply(p.T_world_body.translation());
    p.T_world_body.linear() = T.R * p.T_world_body.linear();
    p.T_world_body.translation() = position;
  }
  return out;
}

// ---------------------------------------------------------------------------------------

ErrorStats ComputeStats(std::vector<double> values) {
  ErrorStats s;
  s.count = values.size();
  if (values.empty()) return s;
  double sum = 0.0, sum_sq = 0.0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
  }
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  double var = 0.0;
  for (double v : values) var += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(var / n);
  std::sort(values.begin(), values.end());
  s.min = values.front();
  s.max = values.back();
  const std::size_t mid = values.size() / 2;
  s.median = values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
  return s;
}

AbsoluteError AbsoluteTrajectoryError(const Trajectory& gt, const Trajectory& est,
                                      AlignmentMode mode) {
  CheckAssociated("AbsoluteTrajectoryError", gt, est);
  AbsoluteError out;
  out.alignment = Align(gt, est, mode);
  std::vector<double> e(gt.size());
  for (std::size_t k = 0; k < gt.size(); ++k) {
    e[k] = (gt[k].T_world_body.translation() -
            out.alignment.T_gt_est.Apply(est[k].T_world_body.translation()))
               .norm();
  }
  out.error_m = ComputeStats(std::move(e));
  return out;
}

double HorizontalAteRmse(const Trajectory& gt, const Trajectory& est) {
  CheckAssociated("HorizontalAteRmse", gt, est);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    sum_sq += (Position(gt[k], true) - Position(est[k], true)).squaredNorm();
  }
  return std::sqrt(sum_sq / static_cast<double>(gt.size()));
}

FinalError ComputeFinalError(const Trajectory& gt, const Trajectory& est) {
  CheckAssociated("ComputeFinalError", gt, est);
  FinalError out;
  out.horizontal_m = (Position(gt.back(), true) - Position(est.back(), true)).norm();
  out.error_3d_m = (Position(gt.back(), false) - Position(est.back(), false)).norm();
  out.gt_path_length_m = PathLength(gt);
  out.pct = PercentOfPath(out.horizontal_m, out.gt_path_length_m);
  return out;
}

// ---------------------------------------------------------------------------------------

void RpeOptions::Validate() const {
  option_check::Positive("delta", delta);
  if (unit == DeltaUnit::kFrames && delta != std::floor(delta)) {
    throw OptionError(
        "delta", "must be a whole number of frames (got " + option_check::Describe(delta) + ")");
  }
}

RpeResult RelativePoseError(const Trajectory& gt, const Trajectory& est,
                            const RpeOptions& options) {
  CheckAssociated("RelativePoseError", gt, est);
  options.Validate();
  const std::size_t n = gt.size();
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  if (options.unit == DeltaUnit::kFrames) {
    const auto d = static_cast<std::size_t>(options.delta);
    const std::size_t step = options.all_pairs ? 1 : d;
    for (std::size_t i = 0; i + d < n; i += step) pairs.emplace_back(i, i + d);
  } else {
    const std::vector<double> dist = CumulativeDistance(gt);
    // j: the first pose whose path length from i reaches delta.
    auto next = [&](std::size_t i) -> std::size_t {
      return static_cast<std::size_t>(
          std::lower_bound(dist.begin() + static_cast<std::ptrdiff_t>(i), dist.end(),
                           dist[i] + options.delta) -
          dist.begin());
    };
    if (options.all_pairs) {
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = next(i);
        if (j >= n) break;  // the path length left only shrinks with i
        pairs.emplace_back(i, j);
      }
    } else {
      for (std::size_t i = 0;;) {
        const std::size_t j = next(i);
        if (j >= n) break;
        pairs.emplace_back(i, j);
        i = j;
      }
    }
  }
  std::vector<double> trans, rot;
  trans.reserve(pairs.size());
  rot.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    const Eigen::Matrix4d E = RelativeError(gt, est, i, j);
    trans.push_back(E.block<3, 1>(0, 3).norm());
    rot.push_back(Angle(E) * 180.0 / kPi);
  }
  RpeResult out;
  out.options = options;
  out.trans_m = ComputeStats(std::move(trans));
  out.rot_deg = ComputeStats(std::move(rot));
  return out;
}

std::vector<FrameMotionSample> FrameToFrameErrors(const Trajectory& gt, const Trajectory& est,
                                                  double min_motion_m) {
  CheckAssociated("FrameToFrameError", gt, est);
  std::vector<FrameMotionSample> samples;
  for (std::size_t i = 0; i + 1 < gt.size(); ++i) {
    const double truth =
        Relative(gt[i].T_world_body, gt[i + 1].T_world_body).block<3, 1>(0, 3).norm();
    if (truth < min_motion_m) continue;
    const Eigen::Matrix4d E = RelativeError(gt, est, i, i + 1);
    FrameMotionSample s;
    s.frame = i;
    s.trans_pct = 100.0 * E.block<3, 1>(0, 3).norm() / truth;
    s.rot_deg = Angle(E) * 180.0 / kPi;
    s.length_ratio =
        Relative(est[i].T_world_body, est[i + 1].T_world_body).block<3, 1>(0, 3).norm() / truth;
    samples.push_back(s);
  }
  return samples;
}

FrameMotionError FrameToFrameError(const Trajectory& gt, const Trajectory& est,
                                   double min_motion_m) {
  std::vector<double> trans, rot, ratio;
  for (const FrameMotionSample& s : FrameToFrameErrors(gt, est, min_motion_m)) {
    trans.push_back(s.trans_pct);
    rot.push_back(s.rot_deg);
    ratio.push_back(s.length_ratio);
  }
  FrameMotionError out;
  out.trans_pct = ComputeStats(std::move(trans));
  out.rot_deg = ComputeStats(std::move(rot));
  out.length_ratio = ComputeStats(std::move(ratio));
  const double gt_length = PathLength(gt);
  out.path_length_ratio = PercentOfPath(PathLength(est), gt_length) / 100.0;
  return out;
}

// ---------------------------------------------------------------------------------------

void SegmentDriftOptions::Validate() const {
  if (lengths_m.empty()) throw OptionError("lengths_m", "must not be empty");
  for (double l : lengths_m) option_check::Positive("lengths_m", l);
  if (step_frames < 1) {
    throw OptionError("step_frames", "must be >= 1 (got " + std::to_string(step_frames) + ")");
  }
}

SegmentDrift SegmentDriftError(const Trajectory& gt, const Trajectory& est,
                               const SegmentDriftOptions& options) {
  CheckAssociated("SegmentDriftError", gt, est);
  options.Validate();
  const std::vector<double> dist = CumulativeDistance(gt);
  const std::size_t n = gt.size();
  const double rad_per_m_to_deg_per_100m = 180.0 / kPi * 100.0;

  SegmentDrift out;
  out.by_length.resize(options.lengths_m.size());
  std::vector<double> t_sum(options.lengths_m.size(), 0.0), r_sum(options.lengths_m.size(), 0.0);
  double t_total = 0.0, r_total = 0.0;
  for (std::size_t first = 0; first < n; first += static_cast<std::size_t>(options.step_frames)) {
    for (std::size_t l = 0; l < options.lengths_m.size(); ++l) {
      const double len = options.lengths_m[l];
      // The devkit's lastFrameFromSegmentLength: the first pose with dist > dist[first] + len.
      const auto it = std::upper_bound(dist.begin() + static_cast<std::ptrdiff_t>(first),
                                       dist.end(), dist[first] + len);
      if (it == dist.end()) continue;
      const auto last = static_cast<std::size_t>(it - dist.begin());
      const Eigen::Matrix4d E = RelativeError(gt, est, first, last);
      const double t_err = E.block<3, 1>(0, 3).norm() / len;
      const double r_err = DevkitAngle(E) / len;
      t_sum[l] += t_err;
      r_sum[l] += r_err;
      t_total += t_err;
      r_total += r_err;
      ++out.by_length[l].segments;
      ++out.segments;
    }
  }
  for (std::size_t l = 0; l < options.lengths_m.size(); ++l) {
    SegmentDrift::ByLength& b = out.by_length[l];
    b.length_m = options.lengths_m[l];
    if (b.segments == 0) continue;
    b.t_rel_pct = 100.0 * t_sum[l] / static_cast<double>(b.segments);
    b.r_rel_deg_per_100m = rad_per_m_to_deg_per_100m * r_sum[l] / static_cast<double>(b.segments);
  }
  if (out.segments > 0) {
    out.t_rel_pct = 100.0 * t_total / static_cast<double>(out.segments);
    out.r_rel_deg_per_100m =
        rad_per_m_to_deg_per_100m * r_total / static_cast<double>(out.segments);
  }
  return out;
}

SegmentDrift KittiOdometryError(const Trajectory& gt, const Trajectory& est) {
  return SegmentDriftError(gt, est, SegmentDriftOptions{});
}

std::optional<double> RpeTransPct(const Trajectory& gt, const Trajectory& est) {
  SegmentDriftOptions options;
  options.lengths_m = {10.0};
  options.step_frames = 1;
  const SegmentDrift d = SegmentDriftError(gt, est, options);
  if (d.segments == 0) return std::nullopt;
  return d.t_rel_pct;
}

// ---------------------------------------------------------------------------------------

std::vector<double> DistancesToPath(const Trajectory& estimate, const Trajectory& reference,
                                    bool horizontal) {
  if (reference.empty()) throw std::invalid_argument("DistancesToPath: empty reference path");
  std::vector<Eigen::Vector3d> ref;
  ref.reserve(reference.size());
  for (const StampedPose& p : reference) ref.push_back(Position(p, horizontal));
  std::vector<double> out;
  out.reserve(estimate.size());
  for (const StampedPose& e : estimate) {
    const Eigen::Vector3d p = Position(e, horizontal);
    double best = (p - ref[0]).squaredNorm();
    for (std::size_t k = 1; k < ref.size(); ++k) {
      const Eigen::Vector3d ab = ref[k] - ref[k - 1];
      const double len_sq = ab.squaredNorm();
      const double u = len_sq > 0.0 ? std::clamp((p - ref[k - 1]).dot(ab) / len_sq, 0.0, 1.0) : 0.0;
      best = std::min(best, (p - (ref[k - 1] + u * ab)).squaredNorm());
    }
    out.push_back(std::sqrt(best));
  }
  return out;
}

std::size_t DistanceHistogram::total() const {
  std::size_t t = below + above;
  for (std::size_t c : counts) t += c;
  return t;
}

DistanceHistogram DistanceErrorHistogram(const Trajectory& estimate, const Trajectory& reference,
                                         const std::vector<double>& edges_m, bool horizontal) {
  if (edges_m.size() < 2) {
    throw std::invalid_argument("DistanceErrorHistogram: needs at least 2 bin edges");
  }
  for (std::size_t k = 0; k < edges_m.size(); ++k) {
    if (!std::isfinite(edges_m[k]) || (k > 0 && !(edges_m[k] > edges_m[k - 1]))) {
      throw std::invalid_argument(
          "DistanceErrorHistogram: bin edges must be finite and strictly increasing");
    }
  }
  DistanceHistogram h;
  h.edges_m = edges_m;
  h.counts.assign(edges_m.size() - 1, 0);
  std::vector<double> d = DistancesToPath(estimate, reference, horizontal);
  for (double v : d) {
    if (v < edges_m.front()) {
      ++h.below;
    } else if (v > edges_m.back()) {
      ++h.above;
    } else {
      // The bin whose [lower, upper) holds v; v == the last edge falls in the last bin.
      const auto it = std::upper_bound(edges_m.begin(), edges_m.end(), v);
      const auto bin =
          std::min(static_cast<std::size_t>(it - edges_m.begin()) - 1, h.counts.size() - 1);
      ++h.counts[bin];
    }
  }
  h.distance_m = ComputeStats(std::move(d));
  return h;
}

// ---------------------------------------------------------------------------------------

void EvaluationOptions::Validate() const {
  option_check::Nested("rpe", rpe);
  option_check::Nested("kitti", kitti);
}

TrajectoryEvaluation EvaluateTrajectory(const Trajectory& gt, const Trajectory& est,
                                        const EvaluationOptions& options) {
  CheckAssociated("EvaluateTrajectory", gt, est);
  options.Validate();
  TrajectoryEvaluation out;
  out.pairs = gt.size();
  out.gt_path_length_m = PathLength(gt);
  out.est_path_length_m = PathLength(est);
  out.ate = AbsoluteTrajectoryError(gt, est, options.align);
  out.ate_rmse_m = HorizontalAteRmse(gt, est);
  out.final_error = ComputeFinalError(gt, est);
  const Trajectory aligned = ApplyAlignment(out.ate.alignment.T_gt_est, est);
  out.final_error_aligned_m =
      (gt.back().T_world_body.translation() - aligned.back().T_world_body.translation()).norm();
  out.rpe = RelativePoseError(gt, aligned, options.rpe);
  out.kitti = SegmentDriftError(gt, aligned, options.kitti);
  out.rpe_trans_pct = RpeTransPct(gt, aligned);
  return out;
}

}  // namespace trackbed::estimation
