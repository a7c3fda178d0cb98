// Estimates handed to the closed loop from outside it (ClosedLoop::ReportEstimate): each
// checked before it is scored — its name free and well formed, its pose a rigid
// transform, one estimate per name and time.
#pragma once

#include <map>
#include <string>

#include <Eigen/Geometry>

#include "trackbed/runner/run_sample.h"

namespace trackbed::runner {

/// The names reported so far and the time of each one's last estimate.
class ReportedEstimates {
 public:
  /// `T_world_body` as estimator `name`'s estimate at `t_s`, with the truth then
  /// `T_world_body_true`; its `name` points into this object. Throws
  /// std::invalid_argument (one line) for a name that is empty, not made of letters,
  /// digits, '_' and '-', or taken (a built-in estimator's, ground_truth); for a matrix
  /// that is not a rigid transform (finite, last row 0 0 0 1, rotation orthonormal to
  /// 1e-6 with determinant +1); for a second estimate of the name at or before the
  /// time of its last.
  ExternalEstimate Accept(const std::string& name, const Eigen::Matrix4d& T_world_body, double t_s,
                          const Eigen::Isometry3d& T_world_body_true);

 private:
  std::map<std::string, double> last_t_;  // estimator → time of its last estimate
};

}  // namespace trackbed::runner
