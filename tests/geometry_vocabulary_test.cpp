// The shared vocabulary of common/: the pinhole camera and its lens against OpenCV's
// own projection, the stereo pair and its KITTI form, the rigid-motion helpers, the
// portable random generator and the grey image's OpenCV view.
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "trackbed/common/option_error.h"
#include "trackbed/common/pinhole_camera.h"
#include "trackbed/common/random.h"
#include "trackbed/common/se3.h"
#include "trackbed/common/stereo_camera.h"
#include "trackbed/common/units.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::geometry {
namespace {

PinholeCamera Kitti06Left() {
  PinholeCamera c;
  c.width_px = 1226;
  c.height_px = 370;
  c.fx = c.fy = 707.0912;
  c.cx = 601.8873;
  c.cy = 183.1104;
  return c;
}

TEST(PinholeCameraTest, ProjectAndBackprojectAreInverse) {
  const PinholeCamera c = Kitti06Left();
  const Eigen::Vector3d p(1.5, -0.4, 12.0);
  const Eigen::Vector2d uv = c.Project(p);
  EXPECT_NEAR(uv.x(), 707.0912 * 1.5 / 12.0 + 601.8873, 1e-12);
  EXPECT_LE((c.Backproject(uv.x(), uv.y(), 12.0) - p).norm(), 1e-12);
  EXPECT_EQ(c.K()(0, 2), c.cx);
  EXPECT_EQ(c.K()(2, 2), 1.0);
}

TEST(PinholeCameraTest, FromFieldOfViewCentresThePrincipalPoint) {
  const PinholeCamera c = PinholeCamera::FromFieldOfView(640, 480, units::Radians(80.0));
  EXPECT_NEAR(c.fx, 320.0 / std::tan(units::Radians(40.0)), 1e-12);
  EXPECT_EQ(c.fx, c.fy);
  EXPECT_EQ(c.cx, 319.5);
  EXPECT_EQ(c.cy, 239.5);
  EXPECT_TRUE(c.distortion.is_zero());
}

TEST(PinholeCameraTest, ValidateNamesTheField) {
  EXPECT_NO_THROW(Kitti06Left().Validate());
  PinholeCamera c = Kitti06Left();
  c.height_px = 0;
  try {
    c.Validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "height_px");
  }
  c = Kitti06Left();
  c.fy = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(c.Validate(), OptionError);
}

// A lens with every coefficient set projects as cv::projectPoints does, and
// Undistort inverts Distort over the image.
TEST(RadialTangentialTest, MatchesOpenCvsProjectionAndInverts) {
  PinholeCamera c = Kitti06Left();
  c.distortion = LensDistortion::RadialTangential(-0.28, 0.07, 0.0008, 0.0011, -0.001);
  const LensDistortion& d = c.distortion;
  const cv::Mat dist = (cv::Mat_<double>(1, 5) << d.k1, d.k2, d.p1, d.p2, d.k3);
  std::vector<cv::Point3d> points;
  for (double x = -6.0; x <= 6.0; x += 1.5) {
    for (double y = -1.5; y <= 1.5; y += 0.75) points.emplace_back(x, y, 10.0);
  }
  std::vector<cv::Point2d> expected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                    cv::Mat(perception::CvCameraMatrix(c)), dist, expected);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p(points[i].x, points[i].y, points[i].z);
    const Eigen::Vector2d uv = c.Project(p);
    EXPECT_NEAR(uv.x(), expected[i].x, 1e-9);
    EXPECT_NEAR(uv.y(), expected[i].y, 1e-9);
    EXPECT_LE((c.Backproject(uv.x(), uv.y(), p.z()) - p).norm(), 1e-9) << i;
  }
}

// An equidistant (fisheye) lens, TUM VI's left camera (ORB-SLAM3's TUM-VI.yaml),
// distorts as cv::fisheye::distortPoints does, and Undistort inverts it out to 80°.
TEST(EquidistantTest, MatchesOpenCvsFisheyeAndInverts) {
  const LensDistortion d = LensDistortion::Equidistant(
      0.0034823894022493434, 0.0007150348452162257, -0.0020532361418706202, 0.00020293673591811182);
  const cv::Matx33d identity = cv::Matx33d::eye();
  const cv::Vec4d coefficients(d.k1, d.k2, d.k3, d.k4);
  for (double angle = 0.0; angle < 80.0; angle += 7.5) {
    const double r = std::tan(units::Radians(angle));
    const Eigen::Vector2d xy(0.6 * r, -0.8 * r);
    std::vector<cv::Point2d> in = {{xy.x(), xy.y()}}, out;
    cv::fisheye::distortPoints(in, out, identity, coefficients);
    const Eigen::Vector2d xy_d = d.Distort(xy);
    EXPECT_NEAR(xy_d.x(), out[0].x, 1e-9) << angle;
    EXPECT_NEAR(xy_d.y(), out[0].y, 1e-9) << angle;
    EXPECT_LE((d.Undistort(xy_d) - xy).norm(), 1e-9 * (1.0 + r)) << angle;
  }
  EXPECT_FALSE(d.is_zero());
  EXPECT_TRUE(LensDistortion::RadialTangential(0, 0, 0, 0).is_zero());
  LensDistortion bad = d;
  bad.p1 = 0.001;
  try {
    bad.Validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "p1");
  }
}

TEST(StereoCameraTest, TriangulateInvertsProjectAndKittiFormRoundTrips) {
  StereoCamera s;
  s.left = Kitti06Left();
  s.baseline_m = 0.537;
  const Eigen::Vector3d p(-2.0, 0.5, 20.0);
  const Eigen::Vector3d z = s.Project(p);
  EXPECT_NEAR(z.x() - z.z(), s.left.fx * s.baseline_m / p.z(), 1e-9);
  EXPECT_LE((s.Triangulate(z.x(), z.y(), z.x() - z.z()) - p).norm(), 1e-9);
  // KITTI's P0 and P1 see the point where the pair does.
  const Eigen::Vector3d l = s.LeftProjection() * p.homogeneous();
  const Eigen::Vector3d r = s.RightProjection() * p.homogeneous();
  EXPECT_NEAR(l.x() / l.z(), z.x(), 1e-9);
  EXPECT_NEAR(r.x() / r.z(), z.z(), 1e-9);
  EXPECT_EQ(s.RightProjection()(0, 3), -707.0912 * 0.537);
  const StereoCamera back = StereoCamera::FromProjections(s.LeftProjection(), s.RightProjection());
  EXPECT_EQ(back.left.fx, s.left.fx);
  EXPECT_EQ(back.left.cy, s.left.cy);
  EXPECT_NEAR(back.baseline_m, 0.537, 1e-15);
  EXPECT_NO_THROW(s.Validate());
  s.baseline_m = 0.0;
  EXPECT_THROW(s.Validate(), OptionError);
  s.baseline_m = 0.537;
  s.left.fx = -1.0;
  try {
    s.Validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "left.fx");
  }
}

TEST(Se3Test, SkewExpAndIncrement) {
  const Eigen::Vector3d v(0.3, -1.2, 2.0), w(-0.7, 0.4, 1.1);
  EXPECT_LE((Skew(v) * w - v.cross(w)).norm(), 1e-15);
  EXPECT_TRUE(ExpSO3(Eigen::Vector3d::Zero()).isIdentity());
  const Eigen::Vector3d phi(0.1, -0.2, 0.3);
  const Eigen::Matrix3d R = ExpSO3(phi);
  EXPECT_NEAR(RotationAngle(R), phi.norm(), 1e-12);
  EXPECT_LE((R * phi - phi).norm(), 1e-12);  // the axis is fixed
  EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
  const Eigen::Isometry3d U = ApplyLeftIncrement(Eigen::Vector3d(0.5, 0.0, 0.0), phi, T);
  EXPECT_LE((U.linear() - R).norm(), 1e-15);
  EXPECT_LE((U.translation() - (R * T.translation() + Eigen::Vector3d(0.5, 0, 0))).norm(), 1e-12);
}

// The generator's draws are fixed by trackbed's code, not a standard library's:
// pinned values, and the moments of each draw.
TEST(RandomTest, DrawsArePinnedAndHaveTheirMoments) {
  random::Generator g(42);
  std::mt19937_64 reference(42);
  EXPECT_EQ(g.Bits(), reference());
  EXPECT_EQ(random::UnitInterval(~0ULL), 1.0 - 0x1.0p-53);
  EXPECT_GT(random::OpenUnitInterval(0), 0.0);
  random::Generator a(7), b(7);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(a.Gaussian(), b.Gaussian());
  // The values every platform must give for seed 1: std::mt19937_64's first output
  // modulo 10, then Box–Muller of the next two.
  random::Generator pinned(1);
  EXPECT_EQ(pinned.UniformIndex(10), 8u);
  EXPECT_EQ(pinned.Gaussian(), -1.9030114103063829);

  constexpr int kDraws = 200000;
  random::Generator r(123);
  double sum = 0.0, sum_sq = 0.0;
  std::vector<int> counts(7, 0);
  for (int i = 0; i < kDraws; ++i) {
    const double x = r.Gaussian();
    sum += x;
    sum_sq += x * x;
    ++counts[r.UniformIndex(7)];
  }
  EXPECT_NEAR(sum / kDraws, 0.0, 0.01);
  EXPECT_NEAR(sum_sq / kDraws, 1.0, 0.01);
  for (int c : counts) EXPECT_NEAR(c, kDraws / 7.0, 5.0 * std::sqrt(kDraws / 7.0));
  for (int i = 0; i < 1000; ++i) ASSERT_LT(r.UniformIndex(3), 3u);
}

TEST(GrayImageViewTest, AsCvMatSharesThePixels) {
  GrayImage image;
  image.width = 4;
  image.height = 3;
  image.pixels = {0, 1, 2, 3, 10, 11, 12, 13, 20, 21, 22, 23};
  const cv::Mat m = perception::AsCvMat(image);
  EXPECT_EQ(m.type(), CV_8UC1);
  EXPECT_EQ(m.size(), cv::Size(4, 3));
  EXPECT_EQ(m.at<std::uint8_t>(2, 1), image.at(1, 2));
  EXPECT_EQ(m.data, image.pixels.data());
}

}  // namespace
}  // namespace trackbed::geometry
