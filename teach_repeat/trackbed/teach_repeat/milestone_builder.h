// The teach phase of visual teach & repeat (Choi & Ha 2011 §II–III; docs/teach_repeat.md):
// cuts the taught image sequence into milestones and records each milestone's features.
//
// Per milestone: Harris corners (absolute threshold, bucketed over a grid so that they
// spread over the image) are detected in its first image and tracked by pyramidal KLT
// from image to image (forward–backward checked, perception::FeatureTracker) to its last
// image; features lost on the way are dropped. The milestone ends
//   - 2D (Chen & Birchfield 2006): after a fixed interval, in images or in distance
//     travelled by the wheel odometry (`interval_unit`);
//   - 3D (Diosi et al. 2007): when the local reconstruction between the first and the
//     current image (5-point essential matrix in RANSAC, triangulation; see
//     teach_repeat_geometry.h) has a mean reprojection error above
//     `max_reprojection_error_px`. The milestone then ends at the previous image, the
//     last whose reconstruction was good enough, and the next starts there. The error
//     is only judged once the odometry baseline reaches `min_baseline_m`: with almost no
//     translation the essential matrix is ill-conditioned and fits anything. A 3D
//     milestone that ends below that baseline (cut short by lost features, a turn in
//     place, the end of the teach) is stored without reconstruction;
//   - both: when fewer than `min_features` features survive tracking into the next image
//     (the milestone ends at the previous image), or at `max_milestone_images`.
// Consecutive milestones share an image: the last image of one is the first of the next.
//
// Scale of a 3D milestone. The essential matrix fixes the translation's direction only.
// We scale it by the wheel odometry's distance between the milestone's first and last
// image (|p_last − p_first| of the planar body poses): the camera translates as the body
// does when the milestone is a straight run; on a turn of Δψ the camera, mounted a
// distance d ahead of the body origin, moves by about d·Δψ more or less than the body,
// which for our short milestones (d ≈ 0.2 m, Δψ of a few degrees) is a relative error
// of ~1 %. Wheel odometry of a tracked robot on slippery ground over-states the distance
// by the slip ratio; that error scales the 3-D points and the repeat's lateral offsets
// (metres), not the steering's direction. 3D teaching therefore needs the odometry pose
// of every image; 2D teaching records it only as metadata (or for distance intervals).
//
// The paper's threshold is 0.1 px, our default. With the motion refitted on all inliers
// (teach_repeat_geometry.h) the error grows smoothly with KLT's drift; on the synthetic
// corridor of the tests it passes 0.1 px after ~0.2–0.35 m (10–19 images at 2 cm),
// close to the paper's average milestone of 19 images (docs/teach_repeat.md). Raise it
// for noisier images.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "trackbed/common/pose2.h"
#include "trackbed/perception/feature_tracker.h"
#include "trackbed/perception/harris_corners.h"
#include "trackbed/teach_repeat/teach_map.h"
#include "trackbed/teach_repeat/teach_repeat_geometry.h"

namespace trackbed::teach_repeat {

/// What a 2D interval counts.
enum class IntervalUnit {
  kImages,    ///< `interval_images` images
  kDistance,  ///< `interval_m` metres of wheel-odometry path
};

/// Harris options for milestone features: the VO's absolute threshold (2e-6, corners of
/// contrast ≳ 0.15 on the 0..1 scale) and a border that keeps the patches inside.
perception::HarrisOptions DefaultMilestoneHarrisOptions();

/// Options of MilestoneBuilder.
struct MilestoneBuilderOptions {
  /// How milestones are cut (and whether they are reconstructed). Not a key of this
  /// struct: a run sets it from `teach_repeat.method`.
  TeachMode mode = TeachMode::k2d;
  /// 2D: what the interval counts.
  IntervalUnit interval_unit = IntervalUnit::kImages;
  /// 2D: images per milestone (last − first), >= 1. The paper's lab teach, 2291 images
  /// in 122 milestones, averages ~19.
  int interval_images = 19;
  /// 2D: odometry path length per milestone [m], > 0.
  double interval_m = 0.2;
  /// 3D: a reconstruction whose mean reprojection error exceeds this [px] ends the
  /// milestone, > 0. The paper's value is 0.1 px.
  double max_reprojection_error_px = 0.1;
  /// 3D: the reprojection error is judged only from this odometry baseline on [m], > 0.
  double min_baseline_m = 0.05;
  /// Both: a milestone ends when fewer features than this survive, >= 8 (the essential
  /// matrix needs at least 5 inliers, the repeat more).
  int min_features = 20;
  /// Both: a milestone ends after this many images at most (last − first), >= 1.
  int max_milestone_images = 100;
  /// Feature detector (`harris.*`, perception/harris_corners.h).
  perception::HarrisOptions harris = DefaultMilestoneHarrisOptions();
  /// Bucketing grid of the detector: cols × rows cells, per_cell corners each, >= 1.
  int grid_cols = 8;
  int grid_rows = 6;
  int features_per_cell = 6;
  /// KLT tracking from image to image, forward–backward checked (`tracker.*`).
  perception::FeatureTrackerOptions tracker;
  /// Essential matrix and triangulation (3D).
  TwoViewOptions two_view;
  /// Side of the stored patches [px], odd, >= 3 (KLT's 11×11 window in Choi & Ha's
  /// implementation). Tracked features closer than half of it to the border are dropped.
  int patch_size_px = 11;

  /// Throws OptionError naming the first invalid field (dotted for nested structs).
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `teach_repeat.milestones`), read and written by the config archive
  /// (trackbed/common/archive.h); mode is set by the run (above).
  template <class Archive>
  void Serialize(Archive* a) {
    a->VisitEnum("interval_unit", &interval_unit,
                 {{"images", IntervalUnit::kImages}, {"distance", IntervalUnit::kDistance}});
    a->Visit("interval_images", &interval_images);
    a->Visit("interval_m", &interval_m);
    a->Visit("max_reprojection_error_px", &max_reprojection_error_px);
    a->Visit("min_baseline_m", &min_baseline_m);
    a->Visit("min_features", &min_features);
    a->Visit("max_milestone_images", &max_milestone_images);
    a->Visit("harris", &harris);
    a->Visit("grid_cols", &grid_cols);
    a->Visit("grid_rows", &grid_rows);
    a->Visit("features_per_cell", &features_per_cell);
    a->Visit("tracker", &tracker);
    a->Visit("two_view", &two_view);
    a->Visit("patch_size_px", &patch_size_px);
  }
};

/// What MilestoneBuilder::AddImage did with one image.
struct TeachStep {
  int image_index = 0;                         ///< index of the image in the teach sequence
  int milestone = 0;                           ///< index of the milestone now open
  bool milestone_closed = false;               ///< a milestone was completed by this image
  MilestoneCut cut = MilestoneCut::kInterval;  ///< why, if closed
  int features = 0;  ///< features of the open milestone tracked into this image
  /// 3D: mean reprojection error of the open milestone's reconstruction at this image
  /// [px]; < 0 when not computed (2D, or below min_baseline_m).
  double reprojection_error_px = -1.0;
};

/// Builds a TeachMap from a stream of images. Stateful; not copyable.
class MilestoneBuilder {
 public:
  /// Throws OptionError for invalid options or intrinsics.
  MilestoneBuilder(const geometry::PinholeCamera& camera,
                   const MilestoneBuilderOptions& options = {});
  MilestoneBuilder(const MilestoneBuilder&) = delete;
  MilestoneBuilder& operator=(const MilestoneBuilder&) = delete;

  /// Adds the next teach image: CV_8UC1 of the camera's size, t_s finite and not
  /// decreasing; `odometry` is the body's wheel-odometry pose at t_s (required in 3D mode
  /// and for distance intervals; metadata otherwise). Throws std::invalid_argument
  /// otherwise (the builder is then unchanged).
  TeachStep AddImage(const cv::Mat& gray, double t_s,
                     const std::optional<geometry::Pose2>& odometry = std::nullopt);

  /// Closes the open milestone (if it spans at least two images) and returns the map.
  /// The builder is empty afterwards and may teach a new route.
  TeachMap Finish();

  /// Writes the key images and features of the milestones completed so far into map
  /// directory `dir` and drops them from memory (SpillKeyImage, SpillFeatures,
  /// teach_map.h), so that teaching a long route holds only the open milestone's; Finish's
  /// map names their files. Throws std::runtime_error naming the file for I/O failures.
  void SpillMilestones(const std::string& dir);
  /// The name SpillMilestones had when it wrote the key images only.
  [[deprecated("use SpillMilestones")]] void SpillKeyImages(const std::string& dir) {
    SpillMilestones(dir);
  }

  /// Milestones completed so far.
  int milestones() const { return static_cast<int>(map_.milestones.size()); }
  const MilestoneBuilderOptions& options() const { return options_; }

 private:
  // The state of the open milestone at one image.
  struct Snapshot {
    int image = -1;
    std::vector<cv::Point2f> first_px, current_px;  // surviving features
    TwoViewGeometry geometry;                       // 3D, when computed
    bool geometry_valid = false;
    double baseline_m = 0.0;
    cv::Mat image_gray;
  };

  // AddImage's steps. The checks of its arguments (throwing std::invalid_argument).
  void CheckImage(const cv::Mat& gray, double t_s,
                  const std::optional<geometry::Pose2>& odometry) const;
  // Whether a feature lies at least half a patch inside the image.
  bool InsidePatchBorder(const cv::Point2f& p) const;
  // A new milestone at image `index` (`image`): its features detected afresh.
  Snapshot Detect(const cv::Mat& image, int index) const;
  // The features of `from` (at the previous image) tracked into image `index` (`gray`,
  // whose pyramid is the current one); 3D: reconstructed once the baseline allows.
  Snapshot Track(const Snapshot& from, const cv::Mat& gray, int index);
  // Why the open milestone ends at `current`, if it does.
  std::optional<MilestoneCut> DueCut(const Snapshot& current) const;
  // Ends the open milestone for `cut` and starts the next; `current` becomes the new
  // milestone at this image.
  void Cut(MilestoneCut cut, const cv::Mat& gray, Snapshot* current);

  void StartMilestone(const Snapshot& at);
  void CloseMilestone(const Snapshot& end, MilestoneCut cut);
  bool Evaluate(Snapshot* s) const;  // 3D reconstruction; true when computed
  double OdometryDistance(int from, int to) const;
  double PathLength(int from, int to) const;

  geometry::PinholeCamera camera_;
  MilestoneBuilderOptions options_;
  perception::FeatureTracker tracker_;
  TeachMap map_;
  bool open_ = false;
  std::size_t spilled_ = 0;             // milestones SpillMilestones wrote
  std::uint64_t spilled_features_ = 0;  // their features
  int first_image_ = 0;
  cv::Mat key_image_;
  Snapshot previous_;  // the open milestone at the previous image
  perception::TrackingPyramid prev_pyramid_, curr_pyramid_;
};

}  // namespace trackbed::teach_repeat
