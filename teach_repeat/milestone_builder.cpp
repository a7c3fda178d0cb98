// The teach phase: cutting milestones and tracking their features (see
// milestone_builder.h).
#include "trackbed/teach_repeat/milestone_builder.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "trackbed/common/option_error.h"
#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::teach_repeat {
namespace {

void AtLeast(const char* field, int value, int minimum) {
  if (value < minimum) {
    throw OptionError(
        field, "must be >= " + std::to_string(minimum) + " (got " + std::to_string(value) + ")");
  }
}

}  // namespace

perception::HarrisOptions DefaultMilestoneHarrisOptions() {
  perception::HarrisOptions h = estimation::DefaultVoHarrisOptions();
  h.border_px = 12;
  h.nms_radius_px = 5;
  return h;
}

void MilestoneBuilderOptions::Validate() const {
  AtLeast("interval_images", interval_images, 1);
  option_check::Positive("interval_m", interval_m);
  option_check::Positive("max_reprojection_error_px", max_reprojection_error_px);
  option_check::Positive("min_baseline_m", min_baseline_m);
  AtLeast("min_features", min_features, 8);
  AtLeast("max_milestone_images", max_milestone_images, 1);
  option_check::Nested("harris", harris);
  AtLeast("grid_cols", grid_cols, 1);
  AtLeast("grid_rows", grid_rows, 1);
  AtLeast("features_per_cell", features_per_cell, 1);
  option_check::Nested("tracker", tracker);
  option_check::Nested("two_view", two_view);
  if (patch_size_px < 3 || patch_size_px % 2 == 0 || patch_size_px > 255) {
    throw OptionError("patch_size_px",
                      "must be odd and in [3, 255] (got " + std::to_string(patch_size_px) + ")");
  }
}

MilestoneBuilder::MilestoneBuilder(const geometry::PinholeCamera& camera,
                                   const MilestoneBuilderOptions& options)
    : camera_(camera), options_(options), tracker_(options.tracker) {
  option_check::Nested("camera", camera_);
  options_.Validate();
  map_.mode = options_.mode;
  map_.camera = camera_;
  map_.patch_size_px = options_.patch_size_px;
}

double MilestoneBuilder::OdometryDistance(int from, int to) const {
  const auto& a = map_.images[static_cast<std::size_t>(from)].odometry;
  const auto& b = map_.images[static_cast<std::size_t>(to)].odometry;
  if (!a || !b) return 0.0;
  return std::hypot(b->x - a->x, b->y - a->y);
}

double MilestoneBuilder::PathLength(int from, int to) const {
  double length = 0.0;
  for (int i = from; i < to; ++i) length += OdometryDistance(i, i + 1);
  return length;
}

bool MilestoneBuilder::Evaluate(Snapshot* s) const {
  s->geometry =
      ReconstructTwoView(camera_, s->first_px, s->current_px, s->baseline_m, options_.two_view);
  s->geometry_valid = s->geometry.ok;
  return s->geometry_valid;
}

void MilestoneBuilder::StartMilestone(const Snapshot& at) {
  first_image_ = at.image;
  key_image_ = at.image_gray;
  open_ = true;
}

void MilestoneBuilder::CloseMilestone(const Snapshot& end, MilestoneCut cut) {
  Milestone m;
  m.first_image = first_image_;
  m.last_image = end.image;
  m.first_t_s = map_.images[static_cast<std::size_t>(first_image_)].t_s;
  m.last_t_s = map_.images[static_cast<std::size_t>(end.image)].t_s;
  m.cut = cut;
  m.key_image = key_image_;
  m.baseline_m = OdometryDistance(first_image_, end.image);
  // Below min_baseline_m (a milestone cut short by lost features, a turn in place, the
  // end of the teach) there is no reconstruction: the essential matrix would be
  // ill-conditioned. The 3D repeat follows such a milestone by the 2D vote.
  const bool reconstructed = options_.mode == TeachMode::k3d && end.geometry_valid;
  m.reconstructed = reconstructed;
  if (reconstructed) {
    m.T_first_last = end.geometry.T_a_b;
    m.reprojection_error_px = end.geometry.reprojection_error_px;
  }
  const int s = options_.patch_size_px;
  for (std::size_t i = 0; i < end.current_px.size(); ++i) {
    if (reconstructed && !end.geometry.inlier[i]) continue;  // RANSAC outliers are dropped
    MilestoneFeature f;
    f.first_px = end.first_px[i];
    f.last_px = end.current_px[i];
    if (reconstructed) f.p_first = end.geometry.p_a[i];
    // Sub-pixel patch centred on the feature, so that the best ZNCC window in the repeat
    // is centred on the feature too.
    cv::getRectSubPix(end.image_gray, cv::Size(s, s), f.last_px, f.patch, CV_8U);
    m.features.push_back(std::move(f));
  }
  map_.milestones.push_back(std::move(m));
  open_ = false;
}

void MilestoneBuilder::CheckImage(const cv::Mat& gray, double t_s,
                                  const std::optional<geometry::Pose2>& odometry) const {
  if (gray.empty() || gray.type() != CV_8UC1 || gray.size() != perception::CvImageSize(camera_)) {
    throw std::invalid_argument("MilestoneBuilder::AddImage: needs a CV_8UC1 image of " +
                                std::to_string(camera_.width_px) + "x" +
                                std::to_string(camera_.height_px) + " px");
  }
  if (!std::isfinite(t_s) || (!map_.images.empty() && t_s < map_.images.back().t_s)) {
    throw std::invalid_argument(
        "MilestoneBuilder::AddImage: time must be finite and not decreasing");
  }
  const bool needs_odometry =
      options_.mode == TeachMode::k3d || options_.interval_unit == IntervalUnit::kDistance;
  if (needs_odometry && !odometry) {
    throw std::invalid_argument(
        "MilestoneBuilder::AddImage: 3D teaching and distance intervals need the odometry pose "
        "of every image");
  }
  if (odometry &&
      !(std::isfinite(odometry->x) && std::isfinite(odometry->y) && std::isfinite(odometry->yaw))) {
    throw std::invalid_argument("MilestoneBuilder::AddImage: odometry pose is not finite");
  }
}

bool MilestoneBuilder::InsidePatchBorder(const cv::Point2f& p) const {
  const float half = static_cast<float>(options_.patch_size_px / 2);
  const float max_x = static_cast<float>(camera_.width_px - 1) - half;
  const float max_y = static_cast<float>(camera_.height_px - 1) - half;
  return !(p.x < half || p.y < half || p.x > max_x || p.y > max_y);
}

MilestoneBuilder::Snapshot MilestoneBuilder::Detect(const cv::Mat& image, int index) const {
  Snapshot s;
  s.image = index;
  s.image_gray = image;
  for (const perception::Corner& c :
       perception::DetectHarrisCornersBucketed(image, options_.harris, options_.grid_cols,
                                               options_.grid_rows, options_.features_per_cell)) {
    if (!InsidePatchBorder(c.position)) continue;
    s.first_px.push_back(c.position);
    s.current_px.push_back(c.position);
  }
  return s;
}

MilestoneBuilder::Snapshot MilestoneBuilder::Track(const Snapshot& from, const cv::Mat& gray,
                                                   int index) {
  Snapshot s;
  s.image = index;
  s.image_gray = gray.clone();
  std::vector<cv::Point2f> tracked;
  std::vector<perception::TrackStatus> status;
  tracker_.Track(prev_pyramid_, curr_pyramid_, from.current_px, &tracked, &status);
  for (std::size_t i = 0; i < tracked.size(); ++i) {
    if (status[i] != perception::TrackStatus::kTracked || !InsidePatchBorder(tracked[i])) {
      continue;
    }
    s.first_px.push_back(from.first_px[i]);
    s.current_px.push_back(tracked[i]);
  }
  s.baseline_m = OdometryDistance(first_image_, index);
  if (options_.mode == TeachMode::k3d && s.baseline_m >= options_.min_baseline_m &&
      static_cast<int>(s.current_px.size()) >= options_.two_view.min_inliers) {
    Evaluate(&s);
  }
  return s;
}

std::optional<MilestoneCut> MilestoneBuilder::DueCut(const Snapshot& current) const {
  const bool too_few = static_cast<int>(current.current_px.size()) < options_.min_features;
  const bool bad_error =
      options_.mode == TeachMode::k3d && current.geometry_valid &&
      current.geometry.reprojection_error_px > options_.max_reprojection_error_px;
  if (too_few) return MilestoneCut::kTooFewFeatures;
  if (bad_error) return MilestoneCut::kReprojectionError;
  const int length = current.image - first_image_;
  bool interval_reached = false;
  if (options_.mode == TeachMode::k2d) {
    interval_reached = options_.interval_unit == IntervalUnit::kImages
                           ? length >= options_.interval_images
                           : PathLength(first_image_, current.image) >= options_.interval_m;
  }
  if (interval_reached) return MilestoneCut::kInterval;
  if (length >= options_.max_milestone_images) return MilestoneCut::kMaxImages;
  return std::nullopt;
}

void MilestoneBuilder::Cut(MilestoneCut cut, const cv::Mat& gray, Snapshot* current) {
  const bool lost_track =
      cut == MilestoneCut::kTooFewFeatures || cut == MilestoneCut::kReprojectionError;
  if (lost_track && previous_.image > first_image_) {
    // End at the previous image, the last good one; the next milestone starts there and
    // its features are tracked into this image at once.
    CloseMilestone(previous_, cut);
    const Snapshot restart = Detect(previous_.image_gray, previous_.image);
    StartMilestone(restart);
    *current = Track(restart, gray, current->image);
    return;
  }
  // At the current image; after lost tracks a one-step milestone, with nothing better
  // to end at.
  CloseMilestone(*current, cut);
  *current = Detect(current->image_gray, current->image);
  StartMilestone(*current);
}

TeachStep MilestoneBuilder::AddImage(const cv::Mat& gray, double t_s,
                                     const std::optional<geometry::Pose2>& odometry) {
  CheckImage(gray, t_s, odometry);
  const int j = static_cast<int>(map_.images.size());
  map_.images.push_back({t_s, odometry});
  tracker_.BuildPyramid(gray, &curr_pyramid_);

  TeachStep step;
  step.image_index = j;
  if (!open_) {
    previous_ = Detect(gray.clone(), j);
    StartMilestone(previous_);
    std::swap(prev_pyramid_, curr_pyramid_);
    step.milestone = milestones();
    step.features = static_cast<int>(previous_.current_px.size());
    return step;
  }

  Snapshot current = Track(previous_, gray, j);
  if (const std::optional<MilestoneCut> cut = DueCut(current)) {
    step.milestone_closed = true;
    step.cut = *cut;
    Cut(*cut, gray, &current);
  }
  previous_ = std::move(current);
  std::swap(prev_pyramid_, curr_pyramid_);
  step.milestone = milestones();
  step.features = static_cast<int>(previous_.current_px.size());
  step.reprojection_error_px =
      previous_.geometry_valid ? previous_.geometry.reprojection_error_px : -1.0;
  return step;
}

void MilestoneBuilder::SpillMilestones(const std::string& dir) {
  for (; spilled_ < map_.milestones.size(); ++spilled_) {
    Milestone& m = map_.milestones[spilled_];
    // A spill that failed half-way is taken up where it stopped.
    if (m.key_image_file.empty()) SpillKeyImage(dir, spilled_, &m);
    SpillFeatures(dir, spilled_features_, options_.patch_size_px, &m);
    spilled_features_ += m.feature_count();
  }
}

TeachMap MilestoneBuilder::Finish() {
  if (open_ && previous_.image > first_image_) CloseMilestone(previous_, MilestoneCut::kEndOfTeach);
  TeachMap done = std::move(map_);
  map_ = TeachMap{};
  map_.mode = options_.mode;
  map_.camera = camera_;
  map_.patch_size_px = options_.patch_size_px;
  open_ = false;
  spilled_ = 0;
  spilled_features_ = 0;
  previous_ = Snapshot{};
  prev_pyramid_ = perception::TrackingPyramid{};
  return done;
}

}  // namespace trackbed::teach_repeat
