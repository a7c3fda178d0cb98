// The teach map of visual teach & repeat (Choi & Ha 2011; docs/teach_repeat.md): the
// milestones cut from the taught image sequence, and its on-disk format.
//
// A milestone spans the teach images first_image … last_image. Its features were
// detected in the first image and tracked (pyramidal KLT, forward–backward checked)
// through every image of the milestone to the last one; both positions are stored
// (Chen & Birchfield 2006). A 3D milestone (Diosi et al. 2007) also stores the local
// reconstruction between its first and last image: the motion T_first_last and each
// feature's 3-D point in the first camera's frame, at metric scale (the scale comes from
// the wheel odometry's distance between the two images; see milestone_builder.h). Every
// feature carries a small patch of its last image, compared with the current image to
// recover features lost to an occluder. The first image of each milestone (its key
// image) is kept: a repeat starts a milestone's tracks by KLT from it.
//
// Key images are most of a map (a 640x480 image is 307 KB; a milestone's features about
// 15 KB), so a long route's map need not hold them all: a milestone's key image may stay
// in its PNG file (Milestone::key_image_file) and be read when the milestone comes near
// (LoadKeyImage, ReleaseKeyImage; the repeater holds a few milestones ahead). A map
// loaded with MapLoading::kOnDemand, and one taught with
// MilestoneBuilder::SpillMilestones, hold their key images that way. Both hold their
// features that way too (a version 2 map; LoadFeatures, ReleaseFeatures, SpillFeatures):
// in memory a feature with its patch takes a few hundred bytes, a 500 m route's map
// hundreds of megabytes.
//
// On disk a map is a directory (docs/teach_repeat.md has the full description):
//   map.json          — format "trackbed.teach_map", version 2: camera, teach images'
//                       times and odometry (metadata), milestones and their feature
//                       counts (version 1, still read, listed the features here too);
//   features.bin      — every feature's positions and 3-D point, milestone by milestone:
//                       magic "TBFEATS1", uint32 40 (bytes per feature), uint32 0, uint64
//                       count, then per feature first_px, last_px (float32) and p_first
//                       (float64), little endian. Binary, so that reading a long route's
//                       map does not build a document of every number first;
//   patches.bin       — every feature's patch, milestone by milestone, feature by feature:
//                       magic "TBPATCH1", uint32 side, uint32 0, uint64 count (little
//                       endian), then count·side² bytes (row-major, 8-bit grey);
//   key_images/NNNNNN.png — milestone NNNNNN's key image (8-bit grey, lossless).
// map.json goes through the config archive (trackbed/common/archive.h; its keys are
// listed beside its file form in teach_map.cpp). Numbers in it are written with the
// shortest representation that reads back to the same double, so Load(Save(map))
// equals map exactly and saving it again gives the same bytes.
//
// Frames: cameras follow OpenCV (x right, y down, z forward); T_a_b maps b coordinates to
// a (p_a = T_a_b · p_b). Pixel coordinates: the centre of the top-left pixel is (0, 0).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "trackbed/common/pinhole_camera.h"
#include "trackbed/common/pose2.h"
#include "trackbed/teach_repeat/milestone_feature.h"

namespace trackbed::teach_repeat {

/// How the milestones were cut.
enum class TeachMode {
  k2d,  ///< fixed interval (Chen & Birchfield 2006): no reconstruction
  k3d,  ///< by the local reconstruction's reprojection error (Diosi et al. 2007)
};
/// "2d", "3d".
const char* ToString(TeachMode mode);
/// Parses "2d" / "3d"; throws std::invalid_argument otherwise.
TeachMode ParseTeachMode(const std::string& text);

/// Why a milestone ended.
enum class MilestoneCut {
  kInterval,           ///< 2D: the fixed interval (images or odometry distance) was reached
  kReprojectionError,  ///< 3D: the next image's reconstruction error passed the threshold
  kTooFewFeatures,     ///< too few features survived tracking into the next image
  kMaxImages,          ///< the milestone reached max_milestone_images
  kEndOfTeach,         ///< the teach sequence ended
};
/// "interval", "reprojection_error", "too_few_features", "max_images", "end_of_teach".
const char* ToString(MilestoneCut cut);
/// Parses the names above; throws std::invalid_argument otherwise.
MilestoneCut ParseMilestoneCut(const std::string& text);

/// A map's feature and patch files (features.bin and patches.bin), from which a map
/// loaded with MapLoading::kOnDemand reads a milestone's features when it comes near.
struct MapFeatureFiles {
  std::string features_path;
  std::string patches_path;
  int patch_size_px = 11;
};

/// Where a milestone's features lie in its map's files: features [first, first + count)
/// of both.
struct FeatureSpan {
  std::shared_ptr<const MapFeatureFiles> files;
  std::uint64_t first = 0;
  std::uint64_t count = 0;
};

/// One milestone: teach images first_image … last_image.
struct Milestone {
  int first_image = 0;     ///< index of the first (key) image in the teach sequence
  int last_image = 0;      ///< index of the last image (the next milestone's first), >= first
  double first_t_s = 0.0;  ///< teach time of the first image [s]
  double last_t_s = 0.0;   ///< teach time of the last image [s]
  MilestoneCut cut = MilestoneCut::kInterval;
  /// The local reconstruction is valid (3D milestones with enough baseline and inliers):
  /// T_first_last and the features' p_first are meaningful.
  bool reconstructed = false;
  /// Pose of the last camera in the first camera's frame (metric) when reconstructed.
  Eigen::Isometry3d T_first_last = Eigen::Isometry3d::Identity();
  /// Mean reprojection error of the reconstruction at the last image [px] (0 if none).
  double reprojection_error_px = 0.0;
  /// Odometry distance between the first and the last image [m]: the reconstruction's
  /// scale (0 when the teach recorded no odometry).
  double baseline_m = 0.0;
  /// The features, when held in memory; empty while they are held in features_file only.
  std::vector<MilestoneFeature> features;
  /// Where the features lie in the map's files, when the map keeps them there (a version 2
  /// map loaded with MapLoading::kOnDemand, or a milestone spilled while teaching, see
  /// SpillFeatures; read by LoadFeatures).
  std::optional<FeatureSpan> features_file;
  /// The first image (CV_8UC1, the camera's size), when held in memory; empty when it
  /// is held in key_image_file only.
  cv::Mat key_image;
  /// The key image's PNG file (an 8-bit grey PNG of the camera's size, as SaveTeachMap
  /// writes), when the map keeps it on disk; empty for a key image held in memory only.
  std::string key_image_file;

  /// Its number of features, held or in its map's files.
  std::size_t feature_count() const {
    return features_file ? static_cast<std::size_t>(features_file->count) : features.size();
  }
};

/// One teach image's metadata.
struct TeachImageRecord {
  double t_s = 0.0;  ///< [s]
  /// Wheel-odometry pose of the body at that time, if the teach recorded it (metadata;
  /// 3D teach uses the distance between poses for the reconstruction's scale).
  std::optional<geometry::Pose2> odometry;
};

/// A taught route.
struct TeachMap {
  TeachMode mode = TeachMode::k2d;
  geometry::PinholeCamera camera;
  int patch_size_px = 11;                ///< side of the stored patches [px], odd, >= 3
  std::vector<TeachImageRecord> images;  ///< every teach image, in order
  std::vector<Milestone> milestones;

  /// Total number of features over all milestones.
  std::size_t feature_count() const;
  /// Throws std::invalid_argument naming the first inconsistency (intrinsics, patch
  /// sizes, image indices out of order or range, key images of the wrong size or type,
  /// non-finite numbers). Save and Load call it.
  void Validate() const;
};

/// The version of the on-disk format this build writes (it reads 1 too).
constexpr int kTeachMapFormatVersion = 2;

/// Reads milestone `m`'s key image from its key_image_file into key_image (nothing when
/// it is held already). Throws std::runtime_error naming the file when it is missing,
/// not a complete PNG, or not an 8-bit grey image of `camera`'s size.
void LoadKeyImage(const geometry::PinholeCamera& camera, Milestone* m);
/// Drops milestone `m`'s key image from memory when it is held in key_image_file too.
void ReleaseKeyImage(Milestone* m);
/// Writes milestone `index`'s key image into map directory `dir` (its key_images/ folder,
/// created if missing), names that file in key_image_file and drops the image from
/// memory. SaveTeachMap into the same `dir` keeps the file. Throws std::runtime_error
/// naming the file for I/O failures, std::invalid_argument when no key image is held.
void SpillKeyImage(const std::string& dir, std::size_t index, Milestone* m);

/// Writes milestone `m`'s features into the feature and patch files of map directory
/// `dir` as their features first … first + count − 1 (the files created anew when `first`
/// is 0; their headers count the features written so far), names that span in
/// features_file and drops the features from memory. Spilling milestone after milestone
/// with `first` the features before them writes the files SaveTeachMap writes; a
/// SaveTeachMap into the same `dir` rewrites them the same. Throws std::runtime_error
/// naming the file for I/O failures (the features then stay held).
void SpillFeatures(const std::string& dir, std::uint64_t first, int patch_size_px, Milestone* m);

/// Writes `map` into directory `dir` (created if missing; an existing map.json,
/// features.bin, patches.bin and key_images/ in it are replaced). Key images held in their files
/// are linked or copied from them, not decoded; features held in the map's files are read
/// from them, and the feature and patch files replaced whole (written beside, then renamed).
/// Throws std::invalid_argument for an invalid map or one whose features lie in `dir`'s
/// feature files at other places than they would be written to (milestones removed or
/// added since it was loaded: save it elsewhere), std::runtime_error naming the file for
/// I/O failures.
void SaveTeachMap(const TeachMap& map, const std::string& dir);

/// How LoadTeachMap reads the key images and the features.
enum class MapLoading {
  kAll,       ///< every key image and feature read and held in memory
  kOnDemand,  ///< key images only checked (a complete 8-bit grey PNG of the camera's
              ///< size, by its header), each milestone naming its file, read by
              ///< LoadKeyImage; in a version 2 map the features and patches files checked
              ///< by their headers and sizes, each milestone naming its span of them, read
              ///< by LoadFeatures
};
/// The name MapLoading had when it decided the key images only.
using KeyImageLoading = MapLoading;

/// Reads a map written by SaveTeachMap. Throws std::runtime_error whose message names
/// the file and what is wrong: a missing directory or file, JSON that does not parse, a
/// wrong format name or version, a missing, unknown or mistyped key (named by its dotted
/// path, e.g. `milestones[3].features[7]`), counts that disagree (features vs patches), a
/// truncated or oversized patch file, a key image that is missing, unreadable or of the
/// wrong size.
TeachMap LoadTeachMap(const std::string& dir, MapLoading loading = MapLoading::kAll);

/// Reads milestone `m`'s features from its map's files (features_file) into features
/// (nothing when they are held already or it names no files). Throws std::runtime_error
/// naming the file and the milestone's features when a file is missing, shorter than the
/// span, or holds a non-finite number.
void LoadFeatures(Milestone* m);
/// Drops milestone `m`'s features from memory when they are held in its map's files too.
void ReleaseFeatures(Milestone* m);

}  // namespace trackbed::teach_repeat
