// When a repeat has passed its active milestone, shared by the 2D repeater (its switch,
// funnel_lane_controller.h) and the 3D repeater (its fallback without a pose,
// milestone_localizer_3d.h): the x-error followed to its minimum (Choi & Ha 2011: "the
// mean x-error stops decreasing and starts to increase"), and the progress through the
// milestone measured as a fraction of the taught image flow (ours). The file comment of
// funnel_lane_controller.h ("The switch", "Progress") gives the readings and why.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "trackbed/teach_repeat/funnel_lane_vote.h"
#include "trackbed/teach_repeat/teach_map.h"

namespace trackbed::teach_repeat {

/// Detects that an error passed its minimum: fed the error every frame, reports once it
/// exceeds its running minimum by the hysteresis.
class ErrorMinimumDetector {
 public:
  /// hysteresis >= 0 [units of the error]; throws std::invalid_argument otherwise.
  explicit ErrorMinimumDetector(double hysteresis);
  /// Starts over (a new milestone).
  void Reset();
  /// Adds one frame's error; returns true once it has risen above minimum + hysteresis
  /// (and from then on, until Reset). Non-finite errors are ignored.
  bool Update(double error);
  double minimum() const { return minimum_; }

 private:
  double hysteresis_;
  double minimum_;
  bool passed_ = false;
};

/// Options of EstimateMilestoneProgress.
struct MilestoneProgressOptions {
  /// Smallest spread (RMS about its mean) of the taught flow F_i over the features for
  /// the progress to be measurable [px], > 0.
  double min_flow_spread_px = 2.0;
  /// Residual beyond which a feature is left out of the second fit [px], > 0 (the
  /// bound is the larger of this and 3 median residuals).
  double outlier_px = 3.0;
  /// Fewest features for a fit, >= 3.
  int min_features = 8;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `teach_repeat.funnel_lane.progress`), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("min_flow_spread_px", &min_flow_spread_px);
    a->Visit("outlier_px", &outlier_px);
    a->Visit("min_features", &min_features);
  }
};

/// Where the current image lies within a milestone (funnel_lane_controller.h,
/// "Progress").
struct MilestoneProgress {
  bool valid = false;       ///< enough features and flow for a fit
  double progress = 0.0;    ///< p: 0 at the key image, 1 at the destination (not clamped)
  double heading_px = 0.0;  ///< c: common x offset [bearing px]; > 0: features lie right
  double pitch_px = 0.0;    ///< b: common y offset [px]
  int features = 0;         ///< used in the final fit
  double rms_px = 0.0;      ///< residual RMS of the final fit [px]
};

/// Fits D_i = p·F_i + (c, b) (funnel_lane_controller.h, "Progress") over the features of
/// `m` whose position in the current image `current_px` is valid (`tracked`; both one
/// per feature).
MilestoneProgress EstimateMilestoneProgress(const geometry::PinholeCamera& camera,
                                            const Milestone& m,
                                            const std::vector<cv::Point2f>& current_px,
                                            const std::vector<bool>& tracked,
                                            const MilestoneProgressOptions& options = {});

/// What the 2D milestone switch follows (funnel_lane_controller.h, "The switch").
enum class SwitchError {
  kMeanAbsolute,  ///< mean_i |e_i| (Choi & Ha's words, literally)
  kMeanOutward,   ///< |mean_i sign(f_d)·e_i| (robust to a lateral offset)
};

namespace detail {

/// The 2D milestone switch: follows the switch error through frame-to-frame changes over
/// the features tracked in both frames — the common shift (rotation) included, so that
/// losing or regaining features on one side of the image moves neither — and detects
/// its minimum.
class MilestoneSwitch {
 public:
  /// hysteresis_px >= 0; throws std::invalid_argument otherwise.
  MilestoneSwitch(double hysteresis_px, SwitchError mode, bool remove_rotation);
  /// A new milestone.
  void Reset();
  /// Feeds one frame; returns true once the error has passed its minimum.
  bool Update(const FunnelFrame& frame);
  /// The current switch error [px].
  double error_px() const;

 private:
  double Term(double error, double outward, double common) const;

  ErrorMinimumDetector detector_;
  SwitchError mode_;
  bool remove_rotation_;
  bool fresh_ = true;
  double common_ = 0.0;       // the common shift (rotation) of the errors [px]
  double accumulated_ = 0.0;  // mean term, followed through its changes
  std::vector<double> last_error_, last_outward_;
};

}  // namespace detail
}  // namespace trackbed::teach_repeat
