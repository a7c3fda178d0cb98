// Estimates reported from outside the loop (see reported_estimates.h).
#include "trackbed/runner/reported_estimates.h"

#include <stdexcept>

namespace trackbed::runner {
namespace {

// The estimators' names a reported estimate may not take: the stack's, and the TUM
// file of ground truth.
constexpr const char* kTakenNames[] = {"wheel_odometry", "wheel_odometry_noslip", "ekf",
                                       "fused",          "visual_odometry",       "ground_truth"};

// Throws std::invalid_argument unless `name` may name a reported estimator.
void CheckEstimatorName(const std::string& name) {
  const auto fail = [&name](const std::string& why) {
    throw std::invalid_argument("estimate \"" + name + "\": " + why);
  };
  if (name.empty()) fail("the name must not be empty");
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) fail("the name may hold only letters, digits, '_' and '-'");
  }
  for (const char* taken : kTakenNames) {
    if (name == taken) fail("the name is taken (the built-in estimators' and ground_truth)");
  }
}

// Throws std::invalid_argument unless `T` is a rigid transform: finite, the last row
// 0 0 0 1, the rotation orthonormal (to 1e-6) with determinant +1.
void CheckRigid(const std::string& name, const Eigen::Matrix4d& T) {
  const auto fail = [&name](const std::string& why) {
    throw std::invalid_argument("estimate \"" + name + "\": not a rigid transform: " + why);
  };
  if (!T.allFinite()) fail("it has non-finite entries");
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) fail("the last row is not 0 0 0 1");
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > 1e-6)
    fail("the rotation is not orthonormal (|R^T R - I| = " + std::to_string(off) + ")");
  if (R.determinant() < 0) fail("the rotation is a reflection (determinant -1)");
}

}  // namespace

ExternalEstimate ReportedEstimates::Accept(const std::string& name, const Eigen::Matrix4d& T,
                                           double t_s, const Eigen::Isometry3d& T_world_body_true) {
  CheckEstimatorName(name);
  CheckRigid(name, T);
  const auto [it, first] = last_t_.try_emplace(name, t_s);
  if (!first) {
    if (!(t_s > it->second)) {
      throw std::invalid_argument("estimate \"" + name + "\": already reported at t = " +
                                  std::to_string(t_s) + " s (one estimate per name and time)");
    }
    it->second = t_s;
  }
  ExternalEstimate e;
  e.name = &it->first;
  e.t_s = t_s;
  e.T_world_body.matrix() = T;
  e.T_world_body_true = T_world_body_true;
  return e;
}

}  // namespace trackbed::runner
