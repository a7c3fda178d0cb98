// The teach map and its on-disk format (see teach_map.h, docs/teach_repeat.md). map.json
// goes through the config archive in its file form (the structs below); patches.bin and
// the key images are written and read here.
#include "trackbed/teach_repeat/teach_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "byte_file.h"
#include "feature_files.h"
#include "trackbed/common/archive.h"
#include "trackbed/common/archive_eigen.h"
#include "trackbed/common/durable_file.h"
#include "trackbed/common/option_error.h"
#include "trackbed/perception/opencv_views.h"

namespace trackbed::teach_repeat {
namespace {

namespace fs = std::filesystem;

constexpr char kMapFile[] = "map.json";
constexpr char kKeyImageDir[] = "key_images";
constexpr char kPatchFile[] = "patches.bin";
constexpr char kFeatureFile[] = "features.bin";

// The oldest map.json this build reads: version 1 listed the features in it.
constexpr int kOldestTeachMapVersion = 1;
// A milestone's features at most (thousands in practice): bounds what a count in
// map.json can make a reader allocate before the feature file is checked.
constexpr std::int64_t kMostFeaturesPerMilestone = 1 << 24;
// map.json's messages say what they found, as scenario files' do.
constexpr archive::Wording kWording = archive::Wording::kDetailed;

std::string KeyImageName(std::size_t milestone) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06zu.png", milestone);
  return std::string(kKeyImageDir) + "/" + name;
}

bool Finite(const cv::Point2f& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// --- map.json's file form, key for key, for the config archive. ---------------------------
//
// These structs mirror the file, not the TeachMap: the counts, file names, format name
// and version are written for readers of the file, images are stored as columns (t_s,
// odometry), poses and features as flat lists of numbers. MapToFile and MapFromFile
// convert, the latter checking what one key cannot check alone (counts against lists,
// image indices against images.count). Every key is required, and a missing key is
// reported before the keys after it (archive::kRequiredAtOnce), as map.json's reader
// always did; unknown keys are rejected. `format` and `version` are checked as soon as
// they are read, so a map of another version is reported as such rather than by its
// other keys.

/// map.json's `format`.
constexpr char kFormatName[] = "trackbed.teach_map";

/// `camera`: the pinhole intrinsics of geometry::PinholeCamera, its image size as
/// `width` and `height` (the map has no lens: teach & repeat take rectified images).
struct CameraFile {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  int width = 0, height = 0;

  geometry::PinholeCamera ToCamera() const {
    geometry::PinholeCamera c;
    c.fx = fx;
    c.fy = fy;
    c.cx = cx;
    c.cy = cy;
    c.width_px = width;
    c.height_px = height;
    return c;
  }
  /// The camera's checks, naming this file's keys.
  void Validate() const {
    try {
      ToCamera().Validate();
    } catch (const OptionError& e) {
      if (e.field() == "width_px") throw OptionError("width", e.reason());
      if (e.field() == "height_px") throw OptionError("height", e.reason());
      throw;
    }
  }

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("fx", &fx, archive::kRequiredAtOnce);
    a->Visit("fy", &fy, archive::kRequiredAtOnce);
    a->Visit("cx", &cx, archive::kRequiredAtOnce);
    a->Visit("cy", &cy, archive::kRequiredAtOnce);
    a->Visit("width", &width, archive::kRequiredAtOnce);
    a->Visit("height", &height, archive::kRequiredAtOnce);
  }
};

/// `images`: every teach image's time and, when recorded, wheel odometry (x, y, yaw),
/// as two lists of `count` entries.
struct ImagesFile {
  std::int64_t count = 0;
  std::vector<double> t_s;
  std::vector<std::optional<Eigen::Vector3d>> odometry;  ///< null: none recorded

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("count", &count, archive::kRequiredAtOnce);
    a->Visit("t_s", &t_s, archive::kRequiredAtOnce);
    a->Visit("odometry", &odometry, archive::kRequiredAtOnce);
  }
};

/// A feature's row: first_px (x, y), last_px (x, y), p_first (x, y, z).
using FeatureRow = Eigen::Matrix<double, 7, 1>;
/// T_first_last's top three rows, row by row.
using PoseRows = Eigen::Matrix<double, 12, 1>;

/// One of `milestones`.
struct MilestoneFile {
  int first_image = 0, last_image = 0;
  double first_t_s = 0.0, last_t_s = 0.0;
  MilestoneCut cut = MilestoneCut::kInterval;
  bool reconstructed = false;
  PoseRows T_first_last = PoseRows::Zero();
  double reprojection_error_px = 0.0;
  double baseline_m = 0.0;
  std::string key_image;  ///< the key image's file, relative to the map's directory
  std::int64_t feature_count = 0;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("first_image", &first_image, archive::kRequiredAtOnce);
    a->Visit("last_image", &last_image, archive::kRequiredAtOnce);
    a->Visit("first_t_s", &first_t_s, archive::kRequiredAtOnce);
    a->Visit("last_t_s", &last_t_s, archive::kRequiredAtOnce);
    a->VisitEnum("cut", &cut,
                 {{ToString(MilestoneCut::kInterval), MilestoneCut::kInterval},
                  {ToString(MilestoneCut::kReprojectionError), MilestoneCut::kReprojectionError},
                  {ToString(MilestoneCut::kTooFewFeatures), MilestoneCut::kTooFewFeatures},
                  {ToString(MilestoneCut::kMaxImages), MilestoneCut::kMaxImages},
                  {ToString(MilestoneCut::kEndOfTeach), MilestoneCut::kEndOfTeach}},
                 archive::kRequiredAtOnce);
    a->Visit("reconstructed", &reconstructed, archive::kRequiredAtOnce);
    a->Visit("T_first_last", &T_first_last, archive::kRequiredAtOnce);
    a->Visit("reprojection_error_px", &reprojection_error_px, archive::kRequiredAtOnce);
    a->Visit("baseline_m", &baseline_m, archive::kRequiredAtOnce);
    a->Visit("key_image", &key_image, archive::kRequiredAtOnce);
    a->Visit("feature_count", &feature_count, archive::kRequiredAtOnce);
  }
};

/// One of `milestones` in a version 1 map.json, which listed the features there.
struct MilestoneFileV1 : MilestoneFile {
  std::vector<FeatureRow> features;

  template <class Archive>
  void Serialize(Archive* a) {
    MilestoneFile::Serialize(a);
    a->Visit("features", &features, archive::kRequiredAtOnce);
  }
};

/// map.json.
struct MapFile {
  std::string format = kFormatName;
  int version = kTeachMapFormatVersion;
  TeachMode mode = TeachMode::k2d;
  CameraFile camera;
  int patch_size_px = 0;
  std::string patches_file;  ///< the patch file, relative to the map's directory
  std::int64_t patch_count = 0;
  std::string features_file;  ///< the feature file (version 2 on), relative to the map's directory
  ImagesFile images;
  std::vector<MilestoneFile> milestones;       // version 2 on
  std::vector<MilestoneFileV1> milestones_v1;  // version 1

  /// Milestone `k` of either version's list.
  const MilestoneFile& milestone(std::size_t k) const {
    return version < 2 ? milestones_v1[k] : milestones[k];
  }
  std::size_t milestone_count() const {
    return version < 2 ? milestones_v1.size() : milestones.size();
  }

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("format", &format, archive::kRequiredAtOnce);
    if (format != kFormatName) {
      a->Fail("format", "expected \"" + std::string(kFormatName) + "\", found \"" + format + "\"");
    }
    a->Visit("version", &version, archive::kRequiredAtOnce);
    if (version < kOldestTeachMapVersion || version > kTeachMapFormatVersion) {
      a->Fail("version", "unsupported version " + std::to_string(version) +
                             " (this build reads versions " +
                             std::to_string(kOldestTeachMapVersion) + " to " +
                             std::to_string(kTeachMapFormatVersion) + ")");
    }
    a->VisitEnum(
        "mode", &mode,
        {{ToString(TeachMode::k2d), TeachMode::k2d}, {ToString(TeachMode::k3d), TeachMode::k3d}},
        archive::kRequiredAtOnce);
    a->Visit("camera", &camera, archive::kRequiredAtOnce);
    a->Visit("patch_size_px", &patch_size_px, archive::kRequiredAtOnce);
    a->Visit("patches_file", &patches_file, archive::kRequiredAtOnce);
    a->Visit("patch_count", &patch_count, archive::kRequiredAtOnce);
    if (version >= 2) a->Visit("features_file", &features_file, archive::kRequiredAtOnce);
    a->Visit("images", &images, archive::kRequiredAtOnce);
    if (version >= 2) {
      a->Visit("milestones", &milestones, archive::kRequiredAtOnce);
    } else {
      a->Visit("milestones", &milestones_v1, archive::kRequiredAtOnce);
    }
  }
};

// --- map.json's file form from a map. -----------------------------------------------------

MilestoneFile MilestoneToFile(const Milestone& m, std::size_t index) {
  MilestoneFile f;
  f.first_image = m.first_image;
  f.last_image = m.last_image;
  f.first_t_s = m.first_t_s;
  f.last_t_s = m.last_t_s;
  f.cut = m.cut;
  f.reconstructed = m.reconstructed;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) f.T_first_last[4 * r + c] = m.T_first_last.matrix()(r, c);
  }
  f.reprojection_error_px = m.reprojection_error_px;
  f.baseline_m = m.baseline_m;
  f.key_image = KeyImageName(index);
  f.feature_count = static_cast<std::int64_t>(m.feature_count());
  return f;
}

MapFile MapToFile(const TeachMap& map) {
  MapFile f;
  f.mode = map.mode;
  const geometry::PinholeCamera& c = map.camera;
  f.camera = {c.fx, c.fy, c.cx, c.cy, c.width_px, c.height_px};
  f.patch_size_px = map.patch_size_px;
  f.patches_file = kPatchFile;
  f.patch_count = static_cast<std::int64_t>(map.feature_count());
  f.features_file = kFeatureFile;
  f.images.count = static_cast<std::int64_t>(map.images.size());
  for (const TeachImageRecord& r : map.images) {
    f.images.t_s.push_back(r.t_s);
    f.images.odometry.push_back(
        r.odometry ? std::optional<Eigen::Vector3d>({r.odometry->x, r.odometry->y, r.odometry->yaw})
                   : std::nullopt);
  }
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    f.milestones.push_back(MilestoneToFile(map.milestones[k], k));
  }
  return f;
}

}  // namespace

// --- Enums. ------------------------------------------------------------------------------

const char* ToString(TeachMode mode) { return mode == TeachMode::k3d ? "3d" : "2d"; }

TeachMode ParseTeachMode(const std::string& text) {
  if (text == "2d") return TeachMode::k2d;
  if (text == "3d") return TeachMode::k3d;
  throw std::invalid_argument("teach mode must be \"2d\" or \"3d\" (got \"" + text + "\")");
}

const char* ToString(MilestoneCut cut) {
  switch (cut) {
    case MilestoneCut::kInterval:
      return "interval";
    case MilestoneCut::kReprojectionError:
      return "reprojection_error";
    case MilestoneCut::kTooFewFeatures:
      return "too_few_features";
    case MilestoneCut::kMaxImages:
      return "max_images";
    case MilestoneCut::kEndOfTeach:
      return "end_of_teach";
  }
  return "unknown";
}

MilestoneCut ParseMilestoneCut(const std::string& text) {
  for (MilestoneCut cut :
       {MilestoneCut::kInterval, MilestoneCut::kReprojectionError, MilestoneCut::kTooFewFeatures,
        MilestoneCut::kMaxImages, MilestoneCut::kEndOfTeach}) {
    if (text == ToString(cut)) return cut;
  }
  throw std::invalid_argument("unknown milestone cut \"" + text + "\"");
}

// --- TeachMap. ----------------------------------------------------------------------------

std::size_t TeachMap::feature_count() const {
  std::size_t n = 0;
  for (const Milestone& m : milestones) n += m.feature_count();
  return n;
}

void TeachMap::Validate() const {
  option_check::Nested("camera", camera);
  if (patch_size_px < 3 || patch_size_px % 2 == 0) {
    throw std::invalid_argument("teach map: patch_size_px must be odd and >= 3 (got " +
                                std::to_string(patch_size_px) + ")");
  }
  for (std::size_t i = 0; i < images.size(); ++i) {
    const TeachImageRecord& r = images[i];
    const bool odometry_ok =
        !r.odometry || (std::isfinite(r.odometry->x) && std::isfinite(r.odometry->y) &&
                        std::isfinite(r.odometry->yaw));
    if (!std::isfinite(r.t_s) || !odometry_ok) {
      throw std::invalid_argument("teach map: images[" + std::to_string(i) +
                                  "]: non-finite time or odometry");
    }
  }
  const int n_images = static_cast<int>(images.size());
  for (std::size_t k = 0; k < milestones.size(); ++k) {
    const Milestone& m = milestones[k];
    const std::string where = "teach map: milestones[" + std::to_string(k) + "]: ";
    if (m.first_image < 0 || m.first_image >= m.last_image || m.last_image >= n_images) {
      throw std::invalid_argument(
          where + "needs 0 <= first_image < last_image < " + std::to_string(n_images) + " (got " +
          std::to_string(m.first_image) + ", " + std::to_string(m.last_image) + ")");
    }
    if (k > 0 && m.first_image < milestones[k - 1].last_image) {
      throw std::invalid_argument(where + "starts before the previous milestone ends");
    }
    if (!std::isfinite(m.first_t_s) || !std::isfinite(m.last_t_s) ||
        !std::isfinite(m.reprojection_error_px) || !std::isfinite(m.baseline_m) ||
        !m.T_first_last.matrix().allFinite()) {
      throw std::invalid_argument(where + "non-finite number");
    }
    const bool on_file_only = m.key_image.empty() && !m.key_image_file.empty();
    if (!on_file_only &&
        (m.key_image.type() != CV_8UC1 || m.key_image.size() != perception::CvImageSize(camera))) {
      throw std::invalid_argument(where + "key image must be CV_8UC1 of the camera's size " +
                                  std::to_string(camera.width_px) + "x" +
                                  std::to_string(camera.height_px));
    }
    for (std::size_t i = 0; i < m.features.size(); ++i) {
      const MilestoneFeature& f = m.features[i];
      if (!Finite(f.first_px) || !Finite(f.last_px) || !f.p_first.allFinite()) {
        throw std::invalid_argument(where + "features[" + std::to_string(i) +
                                    "]: non-finite number");
      }
      if (f.patch.type() != CV_8UC1 || f.patch.rows != patch_size_px ||
          f.patch.cols != patch_size_px) {
        throw std::invalid_argument(where + "features[" + std::to_string(i) +
                                    "]: patch must be CV_8UC1 of " + std::to_string(patch_size_px) +
                                    "x" + std::to_string(patch_size_px) + " px");
      }
    }
  }
}

// --- Save. --------------------------------------------------------------------------------

namespace {

/// Milestone `m`'s key image as a PNG file at `to`: encoded when held in memory, else a
/// hard link to (or, across file systems, a copy of) its file, which is kept. Errors begin
/// with `who`.
void PutKeyImage(const Milestone& m, const fs::path& to, const char* who = "SaveTeachMap") {
  if (!m.key_image.empty()) {
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", m.key_image, png)) {
      throw std::runtime_error(std::string(who) + ": " + to.string() + ": PNG encoding failed");
    }
    WriteFile(to, std::string(png.begin(), png.end()), who);
    return;
  }
  std::error_code ec;
  fs::create_hard_link(m.key_image_file, to, ec);
  if (ec) fs::copy_file(m.key_image_file, to, ec);
  if (ec) {
    throw std::runtime_error(std::string(who) + ": " + to.string() +
                             ": cannot copy the key image " + m.key_image_file + ": " +
                             ec.message());
  }
}

/// The map's key images as a fresh key_images/ in `root`, so that no image of an earlier,
/// longer map remains. They are put into key_images.new/ first and it replaces the old
/// folder only then, so key images held in that folder's files (a spilled or on-demand
/// map saved where it lies) are linked before the folder goes.
void WriteKeyImages(const TeachMap& map, const fs::path& root) {
  const fs::path key_dir = root / kKeyImageDir;
  const fs::path fresh = root / (std::string(kKeyImageDir) + ".new");
  std::error_code ec;
  fs::remove_all(fresh, ec);
  fs::create_directories(fresh, ec);
  if (ec) throw std::runtime_error("SaveTeachMap: " + fresh.string() + ": cannot create directory");
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    const Milestone& m = map.milestones[k];
    const fs::path name = fs::path(KeyImageName(k)).filename();
    if (m.key_image.empty() &&
        fs::equivalent(fs::path(m.key_image_file).parent_path(), key_dir, ec) &&
        fs::path(m.key_image_file).filename() != name) {
      throw std::invalid_argument("SaveTeachMap: milestones[" + std::to_string(k) +
                                  "]: its key image " + m.key_image_file +
                                  " would be replaced by another milestone's");
    }
    PutKeyImage(m, fresh / name);
  }
  fs::remove_all(key_dir, ec);
  if (!ec) fs::rename(fresh, key_dir, ec);
  if (ec) {
    throw std::runtime_error("SaveTeachMap: " + key_dir.string() +
                             ": cannot replace: " + ec.message());
  }
}

}  // namespace

namespace {

/// Milestone `m`'s features: those it holds, or those of its map's files read into
/// `scratch`.
const std::vector<MilestoneFeature>& HeldOrRead(const Milestone& m,
                                                std::vector<MilestoneFeature>* scratch) {
  if (!m.features_file || m.features.size() == m.feature_count()) return m.features;
  Milestone copy;
  copy.features_file = m.features_file;
  LoadFeatures(&copy);
  *scratch = std::move(copy.features);
  return *scratch;
}

/// features.bin's and patches.bin's bytes: every feature, milestone by milestone; a
/// milestone held in its files only is read once.
std::pair<std::string, std::string> FeatureAndPatchBlobs(const TeachMap& map) {
  const std::size_t count = map.feature_count();
  const auto side = static_cast<std::size_t>(map.patch_size_px);
  std::pair<std::string, std::string> blobs{FeatureFileHeader(count),
                                            PatchFileHeader(map.patch_size_px, count)};
  blobs.first.reserve(kRecordHeaderBytes + count * kFeatureRecordBytes);
  blobs.second.reserve(kRecordHeaderBytes + count * side * side);
  std::vector<MilestoneFeature> scratch;
  for (const Milestone& m : map.milestones) {
    for (const MilestoneFeature& f : HeldOrRead(m, &scratch)) {
      PutFeature(f, &blobs.first);
      PutPatch(f, map.patch_size_px, &blobs.second);
    }
  }
  return blobs;
}

/// Hands the features of a checked feature file (ReadFeatureFile) to the milestones, as
/// many to each as map.json counts.
void AssignFeatures(const std::string& blob, const std::vector<std::size_t>& counts,
                    TeachMap* map) {
  std::size_t offset = kRecordHeaderBytes;
  for (std::size_t k = 0; k < map->milestones.size(); ++k) {
    map->milestones[k].features.resize(counts[k]);
    offset = GetFeatures(blob, offset, &map->milestones[k].features);
  }
}

/// Hands the patches of a checked patch file (ReadPatchFile) to the features, milestone
/// by milestone, feature by feature.
void AssignPatches(const std::string& blob, TeachMap* map) {
  std::size_t offset = kRecordHeaderBytes;
  for (Milestone& m : map->milestones) {
    offset = GetPatches(blob, offset, map->patch_size_px, &m.features);
  }
}

}  // namespace

namespace {

/// Refuses to save `map` into `root` when a milestone's features lie in the feature
/// files there at another place than they would be written to (milestones removed or
/// added since the map was loaded or spilled): its span would then name other features.
void CheckFeaturesStayInPlace(const TeachMap& map, const fs::path& root) {
  std::uint64_t first = 0;
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    const Milestone& m = map.milestones[k];
    if (m.features_file && m.features_file->first != first) {
      const MapFeatureFiles& files = *m.features_file->files;
      std::error_code a, b;
      if (fs::equivalent(files.features_path, root / kFeatureFile, a) ||
          fs::equivalent(files.patches_path, root / kPatchFile, b)) {
        throw std::invalid_argument(
            "SaveTeachMap: " + root.string() + ": milestones[" + std::to_string(k) +
            "]'s features would move within the files they are read from; save it elsewhere");
      }
    }
    first += m.feature_count();
  }
}

}  // namespace

void SaveTeachMap(const TeachMap& map, const std::string& dir) {
  map.Validate();
  const fs::path root(dir);
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec || !fs::is_directory(root)) {
    throw std::runtime_error("SaveTeachMap: " + dir + ": cannot create directory");
  }
  CheckFeaturesStayInPlace(map, root);
  // Both made before either file is replaced: features on disk are read from the old ones.
  const auto [features, patches] = FeatureAndPatchBlobs(map);

  WriteKeyImages(map, root);

  WriteFileAtomically(root / kPatchFile, patches);
  WriteFileAtomically(root / kFeatureFile, features);

  // map.json, in its file form, one space per level of indentation.
  WriteFile(root / kMapFile, archive::ToJson(archive::Write(MapToFile(map)), 1) + "\n");
}

// --- Load. --------------------------------------------------------------------------------

namespace {

/// map.json, read into its file form. Throws archive::Error naming the key at fault.
MapFile ReadMapFile(const std::string& text) {
  archive::Node root;
  try {
    root = archive::ParseJson(text);
  } catch (const archive::SyntaxError& e) {
    throw archive::Error("", "not valid JSON (truncated?): " + e.detail());
  }
  MapFile file;
  archive::Read(root, "", kWording, &file);
  return file;
}

/// The teach images' times and odometry, checked against images.count.
void ImagesFromFile(const ImagesFile& images, TeachMap* map) {
  if (images.count < 0) throw archive::Error("images.count", "must be >= 0");
  const auto check_size = [&](const char* key, std::size_t size) {
    if (size != static_cast<std::size_t>(images.count)) {
      throw archive::Error(
          archive::JoinKey("images", key),
          "expected " + std::to_string(images.count) + " entries, found " + std::to_string(size));
    }
  };
  check_size("t_s", images.t_s.size());
  check_size("odometry", images.odometry.size());
  map->images.resize(images.t_s.size());
  for (std::size_t i = 0; i < map->images.size(); ++i) {
    map->images[i].t_s = images.t_s[i];
    if (const std::optional<Eigen::Vector3d>& p = images.odometry[i]) {
      map->images[i].odometry = geometry::Pose2{p->x(), p->y(), p->z()};
    }
  }
}

/// Milestone `f` (at `path`), checked against the milestone before it (nullptr for the
/// first) and the map's number of teach images. Its key image and patches come later.
Milestone MilestoneFromFile(const MilestoneFile& f, const std::string& path,
                            const Milestone* previous, std::size_t image_count) {
  if (f.first_image < 0 || f.first_image >= f.last_image ||
      static_cast<std::size_t>(f.last_image) >= image_count) {
    throw archive::Error(path, "needs 0 <= first_image < last_image < images.count (got " +
                                   std::to_string(f.first_image) + ", " +
                                   std::to_string(f.last_image) + ")");
  }
  if (previous != nullptr && f.first_image < previous->last_image) {
    throw archive::Error(path + ".first_image", "starts before the previous milestone ends");
  }
  if (f.feature_count < 0 || f.feature_count > kMostFeaturesPerMilestone) {
    throw archive::Error(path + ".feature_count",
                         "must be in [0, " + std::to_string(kMostFeaturesPerMilestone) + "] (got " +
                             std::to_string(f.feature_count) + ")");
  }
  Milestone m;
  m.first_image = f.first_image;
  m.last_image = f.last_image;
  m.first_t_s = f.first_t_s;
  m.last_t_s = f.last_t_s;
  m.cut = f.cut;
  m.reconstructed = f.reconstructed;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) m.T_first_last.matrix()(r, c) = f.T_first_last[4 * r + c];
  }
  m.reprojection_error_px = f.reprojection_error_px;
  m.baseline_m = f.baseline_m;
  return m;
}

/// A version 1 milestone's features, listed in map.json, checked against its count.
void FeaturesFromRows(const MilestoneFileV1& f, const std::string& path, Milestone* m) {
  if (static_cast<std::size_t>(f.feature_count) != f.features.size()) {
    throw archive::Error(path, "inconsistent counts: feature_count is " +
                                   std::to_string(f.feature_count) + " but " +
                                   std::to_string(f.features.size()) + " features are listed");
  }
  m->features.resize(f.features.size());
  for (std::size_t i = 0; i < f.features.size(); ++i) {
    const FeatureRow& row = f.features[i];
    // Beyond a float's range the conversion below would be undefined.
    if (!(row.head<4>().cwiseAbs().maxCoeff() <= std::numeric_limits<float>::max())) {
      throw archive::Error(archive::JoinIndex(path + ".features", i),
                           "pixel coordinates beyond a float's range");
    }
    m->features[i].first_px = {static_cast<float>(row[0]), static_cast<float>(row[1])};
    m->features[i].last_px = {static_cast<float>(row[2]), static_cast<float>(row[3])};
    m->features[i].p_first = row.tail<3>();
  }
}

/// The map map.json describes, without key images and patches. Throws archive::Error
/// for what the file form cannot check key by key: the camera, the patch size, counts
/// that disagree with their lists, image indices out of order or range.
TeachMap MapFromFile(const MapFile& f) {
  TeachMap map;
  map.mode = f.mode;
  archive::ValidateAt(f.camera, "camera");
  map.camera = f.camera.ToCamera();
  if (f.patch_size_px < 3 || f.patch_size_px % 2 == 0 || f.patch_size_px > 255) {
    throw archive::Error("patch_size_px", "must be odd and in [3, 255] (got " +
                                              std::to_string(f.patch_size_px) + ")");
  }
  map.patch_size_px = f.patch_size_px;
  ImagesFromFile(f.images, &map);
  std::size_t features = 0;
  for (std::size_t k = 0; k < f.milestone_count(); ++k) {
    const std::string path = archive::JoinIndex("milestones", k);
    const MilestoneFile& mf = f.milestone(k);
    map.milestones.push_back(
        MilestoneFromFile(mf, path, k > 0 ? &map.milestones[k - 1] : nullptr, map.images.size()));
    if (f.version < 2) FeaturesFromRows(f.milestones_v1[k], path, &map.milestones.back());
    features += static_cast<std::size_t>(mf.feature_count);
  }
  if (f.patch_count < 0 || static_cast<std::size_t>(f.patch_count) != features) {
    throw archive::Error("patch_count", "inconsistent counts: " + std::to_string(f.patch_count) +
                                            " patches for " + std::to_string(features) +
                                            " features");
  }
  return map;
}

// A PNG starts with its 8-byte signature and ends with the IEND chunk; checking both
// reports a truncated file as such (and keeps libpng from complaining on stderr).
const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);
const std::string kPngEnd("IEND\xae\x42\x60\x82", 8);

std::string KeyImageSizeWanted(const geometry::PinholeCamera& camera) {
  return ": expected an 8-bit grey image of " + std::to_string(camera.width_px) + "x" +
         std::to_string(camera.height_px) + " px (the camera's size)";
}

/// Key image file `key_path` (of milestone `path`; `who` begins the messages): an 8-bit
/// grey PNG of the camera's size, decoded.
cv::Mat ReadKeyImage(const fs::path& key_path, const std::string& path,
                     const geometry::PinholeCamera& camera, const std::string& who) {
  const std::optional<std::string> png = ReadFile(key_path);
  if (!png) {
    throw std::runtime_error(who + ": " + key_path.string() + ": key image of " + path +
                             " missing or unreadable");
  }
  if (png->size() < 20 || png->compare(0, 8, kPngSignature) != 0 ||
      png->compare(png->size() - 8, 8, kPngEnd) != 0) {
    throw std::runtime_error(who + ": " + key_path.string() +
                             ": not a decodable image (not a complete PNG file: truncated?)");
  }
  const std::vector<unsigned char> bytes(png->begin(), png->end());
  cv::Mat image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  if (image.empty()) {
    throw std::runtime_error(who + ": " + key_path.string() +
                             ": not a decodable image (truncated?)");
  }
  if (image.type() != CV_8UC1 || image.size() != perception::CvImageSize(camera)) {
    throw std::runtime_error(who + ": " + key_path.string() + KeyImageSizeWanted(camera));
  }
  return image;
}

/// Checks key image file `key_path` (of milestone `path`) without decoding it: a complete
/// PNG (signature, IEND at the end) whose header (IHDR) says 8-bit grey of the camera's
/// size. LoadKeyImage decodes it later.
void CheckKeyImageFile(const fs::path& key_path, const std::string& path,
                       const geometry::PinholeCamera& camera) {
  const std::string where = "LoadTeachMap: " + key_path.string();
  std::ifstream in(key_path, std::ios::binary);
  if (!in) throw std::runtime_error(where + ": key image of " + path + " missing or unreadable");
  std::string head(33, '\0'), tail(8, '\0');
  in.read(&head[0], 33);
  const bool head_read = in.gcount() == 33;
  in.seekg(-8, std::ios::end);
  in.read(&tail[0], 8);
  if (!head_read || !in || head.compare(0, 8, kPngSignature) != 0 || tail != kPngEnd ||
      head.compare(12, 4, "IHDR") != 0) {
    throw std::runtime_error(where +
                             ": not a decodable image (not a complete PNG file: truncated?)");
  }
  const auto be32 = [&head](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(head[at + i]);
    return v;
  };
  const bool grey8 = head[24] == 8 && head[25] == 0;
  if (!grey8 || be32(16) != static_cast<std::uint32_t>(camera.width_px) ||
      be32(20) != static_cast<std::uint32_t>(camera.height_px)) {
    throw std::runtime_error(where + KeyImageSizeWanted(camera));
  }
}

// A file map.json names (`key` its path there): relative, and inside the map's folder,
// so that a map read from elsewhere reads nothing outside it.
fs::path FileInMap(const fs::path& root, const std::string& key, const std::string& file) {
  const fs::path relative(file);
  const bool leaves = std::any_of(relative.begin(), relative.end(),
                                  [](const fs::path& part) { return part == ".."; });
  if (file.empty() || relative.is_absolute() || leaves) {
    throw std::runtime_error("LoadTeachMap: " + (root / kMapFile).string() + ": " + key + ": '" +
                             file + "' is not a file inside the map's folder");
  }
  return root / relative;
}

/// Names each milestone's span of a version 2 map's feature and patch files, both
/// checked by their headers and sizes.
void KeepFeaturesInFiles(const fs::path& features, const fs::path& patches, const MapFile& file,
                         TeachMap* map) {
  const auto files = std::make_shared<const MapFeatureFiles>(
      MapFeatureFiles{features.string(), patches.string(), map->patch_size_px});
  std::uint64_t first = 0;
  for (std::size_t k = 0; k < map->milestones.size(); ++k) {
    const auto count = static_cast<std::uint64_t>(file.milestone(k).feature_count);
    map->milestones[k].features_file = FeatureSpan{files, first, count};
    first += count;
  }
  CheckFeatureFile(features, first);
  CheckPatchFile(patches, first, map->patch_size_px);
}

}  // namespace

TeachMap LoadTeachMap(const std::string& dir, MapLoading loading) {
  const fs::path root(dir);
  if (!fs::is_directory(root)) {
    throw std::runtime_error("LoadTeachMap: " + dir + ": no such directory");
  }
  const fs::path map_path = root / kMapFile;
  const std::optional<std::string> text = ReadFile(map_path);
  if (!text) {
    throw std::runtime_error("LoadTeachMap: " + map_path.string() + ": missing or unreadable");
  }
  MapFile file;
  TeachMap map;
  try {
    file = ReadMapFile(*text);
    map = MapFromFile(file);
  } catch (const archive::Error& e) {
    throw std::runtime_error("LoadTeachMap: " + map_path.string() + ": " + e.what());
  }
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    const std::string key = archive::JoinIndex("milestones", k);
    const fs::path key_file = FileInMap(root, key + ".key_image", file.milestone(k).key_image);
    if (loading == MapLoading::kAll) {
      map.milestones[k].key_image = ReadKeyImage(key_file, key, map.camera, "LoadTeachMap");
    } else {
      CheckKeyImageFile(key_file, key, map.camera);
      map.milestones[k].key_image_file = key_file.string();
    }
  }
  const fs::path patches = FileInMap(root, "patches_file", file.patches_file);
  if (file.version >= 2 && loading == MapLoading::kOnDemand) {
    KeepFeaturesInFiles(FileInMap(root, "features_file", file.features_file), patches, file, &map);
  } else {
    if (file.version >= 2) {
      std::vector<std::size_t> counts;
      for (const MilestoneFile& m : file.milestones) {
        counts.push_back(static_cast<std::size_t>(m.feature_count));
      }
      const std::size_t listed = std::accumulate(counts.begin(), counts.end(), std::size_t{0});
      AssignFeatures(ReadFeatureFile(FileInMap(root, "features_file", file.features_file), listed),
                     counts, &map);
    }
    AssignPatches(ReadPatchFile(patches, map.feature_count(), map.patch_size_px), &map);
  }
  try {
    map.Validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("LoadTeachMap: " + map_path.string() + ": " + e.what());
  }
  return map;
}

// --- Key images held on disk. --------------------------------------------------------------

void LoadKeyImage(const geometry::PinholeCamera& camera, Milestone* m) {
  if (!m->key_image.empty()) return;
  if (m->key_image_file.empty()) {
    throw std::runtime_error("LoadKeyImage: the milestone holds no key image and names no file");
  }
  m->key_image = ReadKeyImage(m->key_image_file, "the milestone", camera, "LoadKeyImage");
}

void ReleaseKeyImage(Milestone* m) {
  if (!m->key_image_file.empty()) m->key_image.release();
}

// --- Features held on disk. ----------------------------------------------------------------

void LoadFeatures(Milestone* m) {
  if (!m->features_file || m->features.size() == m->feature_count()) return;
  const FeatureSpan& span = *m->features_file;
  const MapFeatureFiles& files = *span.files;
  const auto side = static_cast<std::uint64_t>(files.patch_size_px);
  std::vector<MilestoneFeature> features(static_cast<std::size_t>(span.count));
  GetFeatures(
      ReadRecords(files.features_path, span.first, span.count, kFeatureRecordBytes, "LoadFeatures"),
      0, &features);
  GetPatches(ReadRecords(files.patches_path, span.first, span.count, side * side, "LoadFeatures"),
             0, files.patch_size_px, &features);
  for (std::size_t i = 0; i < features.size(); ++i) {
    const MilestoneFeature& f = features[i];
    if (!Finite(f.first_px) || !Finite(f.last_px) || !f.p_first.allFinite()) {
      throw std::runtime_error("LoadFeatures: " + files.features_path + ": feature " +
                               std::to_string(span.first + i) + ": non-finite number");
    }
  }
  m->features = std::move(features);
}

void ReleaseFeatures(Milestone* m) {
  if (m->features_file) std::vector<MilestoneFeature>().swap(m->features);
}

void SpillFeatures(const std::string& dir, std::uint64_t first, int patch_size_px, Milestone* m) {
  if (m->features_file) return;  // on file already
  const fs::path root(dir);
  const std::uint64_t count = m->features.size(), total = first + count;
  const auto side = static_cast<std::uint64_t>(patch_size_px);
  std::string features, patches;
  for (const MilestoneFeature& f : m->features) {
    PutFeature(f, &features);
    PutPatch(f, patch_size_px, &patches);
  }
  WriteRecordsAt(root / kFeatureFile, FeatureFileHeader(total), first, kFeatureRecordBytes,
                 features, "SpillFeatures");
  WriteRecordsAt(root / kPatchFile, PatchFileHeader(patch_size_px, total), first, side * side,
                 patches, "SpillFeatures");
  m->features_file =
      FeatureSpan{std::make_shared<const MapFeatureFiles>(MapFeatureFiles{
                      (root / kFeatureFile).string(), (root / kPatchFile).string(), patch_size_px}),
                  first, count};
  std::vector<MilestoneFeature>().swap(m->features);
}

void SpillKeyImage(const std::string& dir, std::size_t index, Milestone* m) {
  if (m->key_image.empty()) {
    throw std::invalid_argument("SpillKeyImage: milestone " + std::to_string(index) +
                                " holds no key image");
  }
  const fs::path file = fs::path(dir) / KeyImageName(index);
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) {
    throw std::runtime_error("SpillKeyImage: " + file.parent_path().string() +
                             ": cannot create directory");
  }
  Milestone on_file;
  on_file.key_image = m->key_image;
  PutKeyImage(on_file, file, "SpillKeyImage");
  m->key_image_file = file.string();
  m->key_image.release();
}

}  // namespace trackbed::teach_repeat
