// KITTI-odometry-layout stereo sequences: reading real KITTI folders (and the
// ones trackbed writes from the simulator), and writing them.
//
// Layout (Geiger et al., CVPR 2012, odometry devkit):
//   image_0/%06d.png   left images, rectified, 8-bit gray
//   image_1/%06d.png   right images
//   calib.txt          `P0: 12 numbers` and `P1: 12 numbers` (3x4, row-major);
//                      real KITTI adds P2:, P3:, Tr: lines, which are ignored
//   times.txt          one time [s] per frame (KITTI writes %e; %f is accepted too)
//   poses.txt          optional ground truth, one 3x4 row-major pose per frame:
//                      T_cam0_camk, the left camera k in the first left camera's
//                      frame. Real KITTI keeps these in poses/NN.txt, outside the
//                      sequence folder, hence the explicit `poses_file` argument.
// KITTI poses carry no timestamps: frame k's time is line k of times.txt.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/common/stereo_camera.h"

namespace trackbed::perception {

/// A KITTI-odometry-layout sequence (see the file comment). Reads the text files on
/// construction; images are read on demand.
class KittiSequence {
 public:
  /// Opens `dir`; `poses_file` overrides where ground truth is read (empty: dir/poses.txt
  /// if present, else no ground truth). Frames are image_0/000000.png … consecutively;
  /// image_1 must hold the same names. Throws std::runtime_error naming the file (and
  /// line) for anything missing or malformed: no calib.txt, no or duplicate P0/P1, a
  /// P0/P1 without 12 numbers, a non-numeric entry, P0 not of the form K [I | 0] or P1
  /// not K [I | t] with a positive baseline, no images, image_0/image_1 disagreeing,
  /// times.txt count ≠ image count or decreasing times, poses count ≠ image count, a
  /// pose that is not a rotation, a missing `poses_file`.
  explicit KittiSequence(const std::filesystem::path& dir,
                         const std::filesystem::path& poses_file = {});

  const std::filesystem::path& directory() const { return dir_; }
  /// The rectified pair of calib.txt's P0 and P1, with frame 0's image size.
  const geometry::StereoCamera& calibration() const { return calibration_; }
  std::size_t size() const { return times_s_.size(); }  ///< number of frames
  /// Size [px] of frame 0's left image; every image loaded is checked against it.
  cv::Size image_size() const { return image_size_; }
  /// Frame times [s], from times.txt, non-decreasing.
  const std::vector<double>& times_s() const { return times_s_; }
  bool has_poses() const { return !poses_.empty(); }
  /// Ground truth T_cam0_camk (left camera k in the first left camera's frame), one per
  /// frame; empty when the sequence has none.
  const std::vector<Eigen::Isometry3d>& poses() const { return poses_; }

  /// Left image of frame i, CV_8UC1. Throws std::out_of_range for i >= size() and
  /// std::runtime_error naming the file if it cannot be read or has another size.
  cv::Mat LoadLeft(std::size_t i) const;
  /// Right image of frame i; as LoadLeft.
  cv::Mat LoadRight(std::size_t i) const;

 private:
  cv::Mat Load(const char* folder, std::size_t i) const;

  std::filesystem::path dir_;
  geometry::StereoCamera calibration_;
  std::vector<double> times_s_;
  std::vector<Eigen::Isometry3d> poses_;
  cv::Size image_size_;
};

/// Writes a KITTI-layout sequence: the same files KittiSequence reads, poses.txt
/// included. Creates `dir`, image_0/ and image_1/; an existing sequence there is
/// replaced (its calib/times/poses files are truncated and its NNNNNN.png images in
/// image_0/ and image_1/ deleted, nothing else). Images are PNG (compression level 1).
/// Not copyable.
class KittiWriter {
 public:
  /// Writes calib.txt with `camera`'s P0 and P1. Throws std::invalid_argument for a
  /// camera without positive fx, fy and baseline, and std::runtime_error if a file
  /// cannot be written.
  KittiWriter(const std::filesystem::path& dir, const geometry::StereoCamera& camera);
  ~KittiWriter();
  KittiWriter(const KittiWriter&) = delete;
  KittiWriter& operator=(const KittiWriter&) = delete;

  /// Appends frame size(): time [s] (finite, non-decreasing), left and right images
  /// (CV_8UC1, all of one size), and the left camera's pose T_cam0_cam in the first left
  /// camera's frame. Throws std::invalid_argument for bad arguments, std::runtime_error
  /// for write failures, std::logic_error after Close().
  void Add(double t_s, const cv::Mat& left, const cv::Mat& right,
           const Eigen::Isometry3d& T_cam0_cam);
  /// Frames written so far.
  std::size_t size() const { return frames_; }
  /// Flushes and closes times.txt and poses.txt; idempotent. Throws std::runtime_error
  /// if the flush fails. The destructor calls it and swallows errors.
  void Close();

 private:
  std::filesystem::path dir_;
  std::ofstream times_;
  std::ofstream poses_;
  std::size_t frames_ = 0;
  cv::Size image_size_;
  double last_t_s_ = 0.0;
  bool closed_ = false;
};

/// Parses one KITTI pose line: 12 numbers, the row-major 3x4 [R | t]. The values are kept
/// as given (not re-orthonormalised), so Format→Parse round-trips bit for bit. Throws
/// std::invalid_argument (message starting "ParseKittiPoseLine:") for a count other than
/// 12, a non-numeric or non-finite entry, or an R with |RᵀR − I| > 1e-3 or det R <= 0.
Eigen::Isometry3d ParseKittiPoseLine(const std::string& line);

/// Formats T as a KITTI pose line (no newline): 12 numbers, row-major 3x4, each in the
/// shortest form that parses back to the same double.
std::string FormatKittiPoseLine(const Eigen::Isometry3d& T);

}  // namespace trackbed::perception
