// Lucas–Kanade tracking: sub-pixel accuracy on a known shift, points that leave the
// image, the forward–backward check on an occluded patch, motion-prior guesses, and
// option validation.
#include "trackbed/perception/feature_tracker.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "textured_images.h"
#include "trackbed/common/option_error.h"

namespace trackbed::perception {
namespace {

using testing_images::Shifted;
using testing_images::Texture;

std::vector<cv::Point2f> Grid(float x0, float x1, float y0, float y1, float step) {
  std::vector<cv::Point2f> points;
  for (float y = y0; y <= y1; y += step) {
    for (float x = x0; x <= x1; x += step) points.emplace_back(x + 0.25f, y + 0.6f);
  }
  return points;
}

TEST(FeatureTrackerTest, SubPixelShiftIsTrackedWithinATenthOfAPixel) {
  const cv::Mat texture = Texture(320, 240, 7);
  const double dx = 3.37, dy = -1.62;
  const cv::Mat prev = Shifted(texture, 0.0, 0.0);
  const cv::Mat curr = Shifted(texture, dx, dy);
  const std::vector<cv::Point2f> points = Grid(30.0f, 290.0f, 30.0f, 210.0f, 20.0f);

  FeatureTracker tracker;
  std::vector<cv::Point2f> tracked;
  std::vector<TrackStatus> status;
  const int n = tracker.Track(prev, curr, points, &tracked, &status);
  EXPECT_EQ(n, static_cast<int>(points.size()));
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(status[i], TrackStatus::kTracked) << "point " << i;
    const double ex = tracked[i].x - (points[i].x + dx);
    const double ey = tracked[i].y - (points[i].y + dy);
    worst = std::max(worst, std::hypot(ex, ey));
  }
  EXPECT_LT(worst, 0.1);
  std::printf("LK on a (%.2f, %.2f) px shift: worst error %.4f px over %zu points\n", dx, dy, worst,
              points.size());
}

TEST(FeatureTrackerTest, LargeShiftNeedsThePyramidOrAGuess) {
  const cv::Mat texture = Texture(320, 240, 11);
  const double dx = 24.6, dy = 9.3;
  const cv::Mat prev = Shifted(texture, 0.0, 0.0);
  const cv::Mat curr = Shifted(texture, dx, dy);
  const std::vector<cv::Point2f> points = Grid(40.0f, 220.0f, 40.0f, 190.0f, 30.0f);

  FeatureTrackerOptions no_pyramid;
  no_pyramid.pyramid_levels = 0;
  FeatureTracker flat(no_pyramid);
  TrackingPyramid p0, p1;
  flat.BuildPyramid(prev, &p0);
  flat.BuildPyramid(curr, &p1);
  std::vector<cv::Point2f> tracked;
  std::vector<TrackStatus> status;
  // Without levels and without a guess, a 26 px motion is beyond a 15 px window ...
  const int blind = flat.Track(p0, p1, points, &tracked, &status);
  EXPECT_LT(blind, static_cast<int>(points.size()) / 2);
  // ... but a guess within a pixel or two of the answer brings every point in.
  tracked.clear();
  for (const cv::Point2f& p : points) {
    tracked.emplace_back(p.x + static_cast<float>(dx) + 1.5f, p.y + static_cast<float>(dy) - 1.0f);
  }
  const int guided = flat.Track(p0, p1, points, &tracked, &status, /*use_initial_guess=*/true);
  EXPECT_EQ(guided, static_cast<int>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (status[i] != TrackStatus::kTracked) continue;
    EXPECT_NEAR(tracked[i].x, points[i].x + dx, 0.1);
    EXPECT_NEAR(tracked[i].y, points[i].y + dy, 0.1);
  }
  // The default pyramid (3 levels) finds it without a guess (the points stay 70 px from
  // the right edge: at the coarsest level, 1/8 scale, a window reaching past the border
  // sees reflected texture).
  FeatureTracker pyramidal;
  EXPECT_EQ(pyramidal.Track(prev, curr, points, &tracked, &status),
            static_cast<int>(points.size()));
}

TEST(FeatureTrackerTest, PointsLeavingTheImageAreDropped) {
  const cv::Mat texture = Texture(320, 240, 3);
  const double dx = 12.0, dy = 0.0;
  const cv::Mat prev = Shifted(texture, 0.0, 0.0);
  const cv::Mat curr = Shifted(texture, dx, dy);
  // Points 2..9 px from the right edge move outside; points further in stay.
  std::vector<cv::Point2f> leaving, staying;
  for (float y = 30.0f; y < 210.0f; y += 20.0f) {
    leaving.emplace_back(319.0f - 2.0f, y);
    leaving.emplace_back(319.0f - 9.0f, y);
    staying.emplace_back(200.0f, y);
  }
  FeatureTracker tracker;
  std::vector<cv::Point2f> tracked;
  std::vector<TrackStatus> status;
  EXPECT_EQ(tracker.Track(prev, curr, leaving, &tracked, &status), 0);
  for (TrackStatus s : status) EXPECT_NE(s, TrackStatus::kTracked) << ToString(s);
  EXPECT_EQ(tracker.Track(prev, curr, staying, &tracked, &status),
            static_cast<int>(staying.size()));

  // A border keeps tracked points that far inside.
  FeatureTrackerOptions with_border;
  with_border.border_px = 130.0;  // x = 212 is within 130 px of the right edge (319)
  FeatureTracker bordered(with_border);
  EXPECT_EQ(bordered.Track(prev, curr, staying, &tracked, &status), 0);
  for (TrackStatus s : status) EXPECT_EQ(s, TrackStatus::kOutOfImage);
}

TEST(FeatureTrackerTest, ForwardBackwardCheckRejectsTracksIntoAnOccluder) {
  const cv::Mat texture = Texture(320, 240, 5);
  const cv::Mat other = Texture(320, 240, 99);
  const cv::Mat prev = Shifted(texture, 0.0, 0.0);
  cv::Mat curr = Shifted(texture, 1.3, 0.8);
  // An occluder: a 60×60 square of unrelated texture over the middle of the image.
  const cv::Rect occluder(130, 90, 60, 60);
  cv::Mat patch;
  other(occluder).convertTo(patch, CV_8U);
  patch.copyTo(curr(occluder));

  std::vector<cv::Point2f> occluded, visible;
  for (float y = 105.0f; y <= 135.0f; y += 5.0f) {
    for (float x = 145.0f; x <= 175.0f; x += 5.0f) occluded.emplace_back(x, y);
  }
  for (float y = 30.0f; y <= 210.0f; y += 30.0f) visible.emplace_back(40.0f, y);

  // One pyramid level: the motion is small, and coarser levels would see past the
  // occluder's edge and place the occluded points where they truly are (behind it).
  FeatureTrackerOptions no_check;
  no_check.pyramid_levels = 0;
  no_check.max_forward_backward_px = 0.0;
  FeatureTracker unchecked(no_check);
  FeatureTrackerOptions check = no_check;
  check.max_forward_backward_px = FeatureTrackerOptions{}.max_forward_backward_px;  // 0.5 px
  FeatureTracker checked(check);
  std::vector<cv::Point2f> tracked;
  std::vector<TrackStatus> status;
  const int accepted_without_check = unchecked.Track(prev, curr, occluded, &tracked, &status);
  const int accepted_with_check = checked.Track(prev, curr, occluded, &tracked, &status);
  int rejected_by_fb = 0;
  for (TrackStatus s : status) rejected_by_fb += s == TrackStatus::kForwardBackward ? 1 : 0;
  // LK alone accepts nearly every track into the occluder; the check rejects nearly all
  // (a track that barely moves in unrelated texture either way can slip through).
  EXPECT_GT(accepted_without_check, static_cast<int>(occluded.size()) * 8 / 10);
  EXPECT_LT(accepted_with_check, static_cast<int>(occluded.size()) / 10);
  EXPECT_GE(rejected_by_fb, accepted_without_check - accepted_with_check);
  std::printf("tracks into an occluder accepted: %d of %zu without, %d with the check\n",
              accepted_without_check, occluded.size(), accepted_with_check);
  // Points away from the occluder pass the check.
  EXPECT_EQ(checked.Track(prev, curr, visible, &tracked, &status),
            static_cast<int>(visible.size()));
}

TEST(FeatureTrackerTest, EmptyInputAndMismatchedArguments) {
  const cv::Mat image = Shifted(Texture(64, 48, 1), 0.0, 0.0);
  FeatureTracker tracker;
  std::vector<cv::Point2f> tracked;
  std::vector<TrackStatus> status;
  EXPECT_EQ(tracker.Track(image, image, {}, &tracked, &status), 0);
  EXPECT_TRUE(tracked.empty());
  EXPECT_TRUE(status.empty());

  TrackingPyramid a, b;
  EXPECT_THROW(tracker.Track(a, b, {{10.0f, 10.0f}}, &tracked, &status), std::invalid_argument);
  tracker.BuildPyramid(image, &a);
  tracker.BuildPyramid(image, &b);
  tracked.clear();  // a guess of the wrong size
  EXPECT_THROW(tracker.Track(a, b, {{10.0f, 10.0f}}, &tracked, &status, true),
               std::invalid_argument);
  const cv::Mat color(48, 64, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_THROW(tracker.BuildPyramid(color, &a), std::invalid_argument);
}

TEST(FeatureTrackerTest, InvalidOptionsNameTheField) {
  const auto field_of = [](const FeatureTrackerOptions& o) {
    try {
      o.Validate();
    } catch (const OptionError& e) {
      return e.field();
    }
    return std::string("(valid)");
  };
  FeatureTrackerOptions o;
  EXPECT_EQ(field_of(o), "(valid)");
  o.window_px = 14;
  EXPECT_EQ(field_of(o), "window_px");
  o = {};
  o.pyramid_levels = -1;
  EXPECT_EQ(field_of(o), "pyramid_levels");
  o = {};
  o.max_iterations = 0;
  EXPECT_EQ(field_of(o), "max_iterations");
  o = {};
  o.epsilon_px = 0.0;
  EXPECT_EQ(field_of(o), "epsilon_px");
  o = {};
  o.max_forward_backward_px = -1.0;
  EXPECT_EQ(field_of(o), "max_forward_backward_px");
  o = {};
  o.border_px = -0.5;
  EXPECT_EQ(field_of(o), "border_px");
  o = {};
  o.window_px = 3;
  EXPECT_THROW(FeatureTracker{o}, OptionError);
}

}  // namespace
}  // namespace trackbed::perception
