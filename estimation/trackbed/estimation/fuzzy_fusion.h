// Fuzzy fusion of wheel and visual odometry (Ham et al. 2012, §4).
//
// The weight w of wheel odometry comes from a fuzzylite engine whose rule base
// (the paper's Table 1) and membership functions live in an FLL file — by
// default estimation/rules/ham2012_fusion.fll, built into the binary; users
// may load their own. The fused estimate composes per-step motion
// increments, ΔX = w·ΔX_WO + (1 − w)·ΔX_VO (eq. 9 applied to increments), so
// whichever estimator drifted earlier does not drag the fused pose back.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "trackbed/common/pose2.h"

namespace fl {
class Engine;
class InputVariable;
class OutputVariable;
}  // namespace fl

namespace trackbed::estimation {

/// Options of the fusion of wheel and visual odometry (LocalizationStack).
struct FusionOptions {
  /// FLL rule file for the fusion weight (FuzzyFusionWeight); empty: the built-in Ham et
  /// al. Table 1.
  std::string rules_file;
  /// Time constant with which the wheel weight w may rise [s], >= 0 (0: the rule's
  /// value each frame; FusionWeightRise). It falls at once. The slip estimate lags the
  /// ground by its filter and hold times, so the wheels' errors outlast the slip episode
  /// that caused them (and cancel with the errors of its onset); a weight that returned
  /// to the wheels as fast as the estimated slip fades would keep one half of each such
  /// pair.
  double weight_rise_time_s = 3.0;
  /// Which method is the `fused` estimator: kHam2012, the paper's fuzzy weight
  /// (eq. 9); kCovariance, the gyro-led wheel odometry as the prediction and VO's
  /// planar motion as a measurement weighed by its covariance (CovarianceFusion), with
  /// the paper's beside it as `fused_ham2012`.
  enum class Method { kHam2012, kCovariance };
  Method method = Method::kHam2012;
  /// kCovariance: the standard deviation of the wheels' forward speed over a frame
  /// interval on ground that does not slip [m/s], > 0: about a tick of the encoders (0.15
  /// mm) per 0.1 s frame. The prediction's forward σ is this plus the slip estimate's
  /// size (the larger track's), times the interval.
  double wheel_speed_std_mps = 0.002;
  /// kCovariance: the wheels' lateral speed σ [m/s], > 0 (they assume none; the tracks'
  /// side slip reaches 0.08 m/s on slopes, docs/localization.md "The EKF baseline").
  double wheel_lateral_speed_std_mps = 0.05;
  /// kCovariance: the probability inside the innovation gate, in (0, 1): a VO motion
  /// whose Mahalanobis distance from the prediction lies beyond this quantile of χ²
  /// (3 degrees of freedom; 1 for the gyro-led wheel odometry's rotation alone) is not
  /// used.
  double gate_probability = 0.999;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The keys of these fields (e.g. the scenario's `estimation.fusion.*`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("rules_file", &rules_file);
    a->Visit("weight_rise_time_s", &weight_rise_time_s);
    a->VisitEnum("method", &method,
                 {{"ham2012", Method::kHam2012}, {"covariance", Method::kCovariance}});
    a->Visit("wheel_speed_std_mps", &wheel_speed_std_mps);
    a->Visit("wheel_lateral_speed_std_mps", &wheel_lateral_speed_std_mps);
    a->Visit("gate_probability", &gate_probability);
  }
};

/// The fuzzy decision w(slip velocity, number of features). Not copyable.
class FuzzyFusionWeight {
 public:
  /// From FLL text; `source` names it in errors. The engine needs inputs
  /// `slip_velocity` [m/s] and `features` [count] and output `w` in [0, 1];
  /// throws std::invalid_argument naming `source` otherwise.
  FuzzyFusionWeight(const std::string& fll_text, const std::string& source);
  /// The shipped rule base (Ham et al. Table 1).
  FuzzyFusionWeight();
  /// Reads an FLL file; throws std::runtime_error naming it when unreadable.
  static FuzzyFusionWeight FromFile(const std::filesystem::path& path);
  ~FuzzyFusionWeight();
  FuzzyFusionWeight(FuzzyFusionWeight&&) noexcept;
  FuzzyFusionWeight& operator=(FuzzyFusionWeight&&) noexcept;

  /// w for the larger track |slip velocity| [m/s] and the VO inlier count;
  /// inputs beyond the variables' ranges are clamped to them.
  double Weight(double slip_velocity_mps, double features);

  /// The shipped FLL text.
  static const char* DefaultRules();

 private:
  std::unique_ptr<fl::Engine> engine_;
  fl::InputVariable* slip_ = nullptr;
  fl::InputVariable* features_ = nullptr;
  fl::OutputVariable* w_ = nullptr;
};

/// Composes fused motion increments into a planar pose.
class FusedOdometry {
 public:
  explicit FusedOdometry(const geometry::Pose2& initial_pose) : pose_(initial_pose) {}

  /// One fusion step over a camera interval: the wheel-odometry increment and,
  /// when visual odometry produced a motion, its increment, blended with the
  /// wheel weight `w`. Without a VO increment the wheel increment is taken
  /// whole (a failed VO frame has no motion to weigh).
  void Add(const geometry::Pose2& wheel_increment,
           const std::optional<geometry::Pose2>& vo_increment, double w);

  const geometry::Pose2& pose() const { return pose_; }

 private:
  geometry::Pose2 pose_;
};

}  // namespace trackbed::estimation
