// The teach map and its on-disk format (see teach_map.h, docs/teach_repeat.md).
#include "trackbed/teach_repeat/teach_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "trackbed/common/option_error.h"

namespace trackbed::teach_repeat {
namespace {

namespace fs = std::filesystem;
using OrderedJson = nlohmann::ordered_json;
using Json = nlohmann::json;

constexpr char kFormatName[] = "trackbed.teach_map";
constexpr char kMapFile[] = "map.json";
constexpr char kPatchFile[] = "patches.bin";
constexpr char kKeyImageDir[] = "key_images";
constexpr char kPatchMagic[8] = {'T', 'B', 'P', 'A', 'T', 'C', 'H', '1'};
constexpr std::size_t kPatchHeaderBytes = 8 + 4 + 4 + 8;

std::string KeyImageName(std::size_t milestone) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06zu.png", milestone);
  return std::string(kKeyImageDir) + "/" + name;
}

bool Finite(const cv::Point2f& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// --- Little-endian integers, independent of the host's byte order. -----------------------

void PutUint(std::string* out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out->push_back(static_cast<char>((value >> (8 * i)) & 0xFFu));
}

std::uint64_t GetUint(const std::string& in, std::size_t offset, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) {
    value |= static_cast<std::uint64_t>(static_cast<unsigned char>(in[offset + i])) << (8 * i);
  }
  return value;
}

void WriteFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out)
    throw std::runtime_error("SaveTeachMap: " + path.string() + ": cannot open for writing");
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error("SaveTeachMap: " + path.string() + ": write failed");
}

std::optional<std::string> ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// --- Writing. ---------------------------------------------------------------------------

OrderedJson OdometryJson(const std::optional<estimation::Pose2>& pose) {
  if (!pose) return nullptr;
  return OrderedJson::array({pose->x, pose->y, pose->yaw});
}

OrderedJson MilestoneJson(const Milestone& m, std::size_t index) {
  OrderedJson j;
  j["first_image"] = m.first_image;
  j["last_image"] = m.last_image;
  j["first_t_s"] = m.first_t_s;
  j["last_t_s"] = m.last_t_s;
  j["cut"] = ToString(m.cut);
  j["reconstructed"] = m.reconstructed;
  OrderedJson T = OrderedJson::array();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) T.push_back(m.T_first_last.matrix()(r, c));
  }
  j["T_first_last"] = T;
  j["reprojection_error_px"] = m.reprojection_error_px;
  j["baseline_m"] = m.baseline_m;
  j["key_image"] = KeyImageName(index);
  j["feature_count"] = m.features.size();
  OrderedJson features = OrderedJson::array();
  for (const MilestoneFeature& f : m.features) {
    // float → double is exact, and so is the way back on loading.
    features.push_back(
        OrderedJson::array({static_cast<double>(f.first_px.x), static_cast<double>(f.first_px.y),
                            static_cast<double>(f.last_px.x), static_cast<double>(f.last_px.y),
                            f.p_first.x(), f.p_first.y(), f.p_first.z()}));
  }
  j["features"] = std::move(features);
  return j;
}

// --- Reading, with the path of every value in the error messages. -------------------------

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void Fail(const std::string& where, const std::string& what) const {
    throw std::runtime_error("LoadTeachMap: " + file_ + (where.empty() ? "" : ": " + where) + ": " +
                             what);
  }

  const Json& Key(const Json& object, const char* key, const std::string& path) const {
    if (!object.is_object()) Fail(path, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) Fail(Join(path, key), "missing");
    return *it;
  }

  double Number(const Json& j, const std::string& path) const {
    if (!j.is_number()) Fail(path, "expected a number");
    const double value = j.get<double>();
    if (!std::isfinite(value)) Fail(path, "not a finite number");
    return value;
  }

  std::int64_t Integer(const Json& j, const std::string& path) const {
    if (!j.is_number_integer()) Fail(path, "expected an integer");
    return j.get<std::int64_t>();
  }

  bool Boolean(const Json& j, const std::string& path) const {
    if (!j.is_boolean()) Fail(path, "expected true or false");
    return j.get<bool>();
  }

  std::string String(const Json& j, const std::string& path) const {
    if (!j.is_string()) Fail(path, "expected a string");
    return j.get<std::string>();
  }

  const Json& Array(const Json& j, const std::string& path, std::size_t expected = kAny) const {
    if (!j.is_array()) Fail(path, "expected an array");
    if (expected != kAny && j.size() != expected) {
      Fail(path,
           "expected " + std::to_string(expected) + " entries, found " + std::to_string(j.size()));
    }
    return j;
  }

  std::optional<estimation::Pose2> Odometry(const Json& j, const std::string& path) const {
    if (j.is_null()) return std::nullopt;
    Array(j, path, 3);
    return estimation::Pose2{Number(j[0], path + "[0]"), Number(j[1], path + "[1]"),
                             Number(j[2], path + "[2]")};
  }

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string Index(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
  }

  static constexpr std::size_t kAny = static_cast<std::size_t>(-1);

 private:
  std::string file_;
};

}  // namespace

// --- CameraIntrinsics, enums. -------------------------------------------------------------

CameraIntrinsics CameraIntrinsics::FromCalibration(const geometry::StereoCamera& calibration,
                                                   cv::Size image_size) {
  CameraIntrinsics c;
  c.fx = calibration.left.fx;
  c.fy = calibration.left.fy;
  c.cx = calibration.left.cx;
  c.cy = calibration.left.cy;
  c.width = image_size.width;
  c.height = image_size.height;
  c.Validate();
  return c;
}

cv::Matx33d CameraIntrinsics::K() const { return {fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0}; }

void CameraIntrinsics::Validate() const {
  option_check::Positive("fx", fx);
  option_check::Positive("fy", fy);
  option_check::Finite("cx", cx);
  option_check::Finite("cy", cy);
  if (width <= 0) throw OptionError("width", "must be > 0 (got " + std::to_string(width) + ")");
  if (height <= 0) throw OptionError("height", "must be > 0 (got " + std::to_string(height) + ")");
}

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
  for (const Milestone& m : milestones) n += m.features.size();
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
    if (m.key_image.type() != CV_8UC1 || m.key_image.size() != camera.size()) {
      throw std::invalid_argument(where + "key image must be CV_8UC1 of the camera's size " +
                                  std::to_string(camera.width) + "x" +
                                  std::to_string(camera.height));
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

void SaveTeachMap(const TeachMap& map, const std::string& dir) {
  map.Validate();
  const fs::path root(dir);
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec || !fs::is_directory(root)) {
    throw std::runtime_error("SaveTeachMap: " + dir + ": cannot create directory");
  }

  // Key images: a fresh key_images/ so that no image of an earlier, longer map remains.
  const fs::path key_dir = root / kKeyImageDir;
  fs::remove_all(key_dir, ec);
  fs::create_directories(key_dir, ec);
  if (ec)
    throw std::runtime_error("SaveTeachMap: " + key_dir.string() + ": cannot create directory");
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", map.milestones[k].key_image, png)) {
      throw std::runtime_error("SaveTeachMap: " + (root / KeyImageName(k)).string() +
                               ": PNG encoding failed");
    }
    WriteFile(root / KeyImageName(k), std::string(png.begin(), png.end()));
  }

  // Patches.
  const std::size_t count = map.feature_count();
  const std::size_t side = static_cast<std::size_t>(map.patch_size_px);
  std::string patches(kPatchMagic, kPatchMagic + 8);
  PutUint(&patches, side, 4);
  PutUint(&patches, 0, 4);
  PutUint(&patches, count, 8);
  patches.reserve(kPatchHeaderBytes + count * side * side);
  for (const Milestone& m : map.milestones) {
    for (const MilestoneFeature& f : m.features) {
      for (int r = 0; r < f.patch.rows; ++r) {
        const char* row = reinterpret_cast<const char*>(f.patch.ptr<unsigned char>(r));
        patches.append(row, side);
      }
    }
  }
  WriteFile(root / kPatchFile, patches);

  // map.json.
  OrderedJson j;
  j["format"] = kFormatName;
  j["version"] = kTeachMapFormatVersion;
  j["mode"] = ToString(map.mode);
  j["camera"] = {{"fx", map.camera.fx}, {"fy", map.camera.fy},       {"cx", map.camera.cx},
                 {"cy", map.camera.cy}, {"width", map.camera.width}, {"height", map.camera.height}};
  j["patch_size_px"] = map.patch_size_px;
  j["patches_file"] = kPatchFile;
  j["patch_count"] = count;
  OrderedJson times = OrderedJson::array(), odometry = OrderedJson::array();
  for (const TeachImageRecord& r : map.images) {
    times.push_back(r.t_s);
    odometry.push_back(OdometryJson(r.odometry));
  }
  j["images"] = {{"count", map.images.size()}, {"t_s", times}, {"odometry", odometry}};
  OrderedJson milestones = OrderedJson::array();
  for (std::size_t k = 0; k < map.milestones.size(); ++k) {
    milestones.push_back(MilestoneJson(map.milestones[k], k));
  }
  j["milestones"] = std::move(milestones);
  WriteFile(root / kMapFile, j.dump(1) + "\n");
}

// --- Load. --------------------------------------------------------------------------------

namespace {

/// map.json, parsed; throws when it is missing, unreadable or not JSON.
Json ReadMapJson(const fs::path& map_path, const Reader& rd) {
  const std::optional<std::string> text = ReadFile(map_path);
  if (!text)
    throw std::runtime_error("LoadTeachMap: " + map_path.string() + ": missing or unreadable");
  Json j;
  try {
    j = Json::parse(*text);
  } catch (const Json::exception& e) {
    rd.Fail("", std::string("not valid JSON (truncated?): ") + e.what());
  }
  return j;
}

/// Throws unless map.json names this format and the version this build reads.
void CheckFormat(const Reader& rd, const Json& j) {
  const std::string format = rd.String(rd.Key(j, "format", ""), "format");
  if (format != kFormatName) {
    rd.Fail("format", "expected \"" + std::string(kFormatName) + "\", found \"" + format + "\"");
  }
  const std::int64_t version = rd.Integer(rd.Key(j, "version", ""), "version");
  if (version != kTeachMapFormatVersion) {
    rd.Fail("version", "unsupported version " + std::to_string(version) +
                           " (this build reads version " + std::to_string(kTeachMapFormatVersion) +
                           ")");
  }
}

/// The map's teach mode, camera and patch size.
void ReadModeCameraAndPatchSize(const Reader& rd, const Json& j, TeachMap* map) {
  try {
    map->mode = ParseTeachMode(rd.String(rd.Key(j, "mode", ""), "mode"));
  } catch (const std::invalid_argument& e) {
    rd.Fail("mode", e.what());
  }
  const Json& cam = rd.Key(j, "camera", "");
  map->camera.fx = rd.Number(rd.Key(cam, "fx", "camera"), "camera.fx");
  map->camera.fy = rd.Number(rd.Key(cam, "fy", "camera"), "camera.fy");
  map->camera.cx = rd.Number(rd.Key(cam, "cx", "camera"), "camera.cx");
  map->camera.cy = rd.Number(rd.Key(cam, "cy", "camera"), "camera.cy");
  map->camera.width = static_cast<int>(rd.Integer(rd.Key(cam, "width", "camera"), "camera.width"));
  map->camera.height =
      static_cast<int>(rd.Integer(rd.Key(cam, "height", "camera"), "camera.height"));
  try {
    map->camera.Validate();
  } catch (const OptionError& e) {
    rd.Fail("camera." + e.field(), e.reason());
  }
  const std::int64_t patch_size = rd.Integer(rd.Key(j, "patch_size_px", ""), "patch_size_px");
  if (patch_size < 3 || patch_size % 2 == 0 || patch_size > 255) {
    rd.Fail("patch_size_px",
            "must be odd and in [3, 255] (got " + std::to_string(patch_size) + ")");
  }
  map->patch_size_px = static_cast<int>(patch_size);
}

/// The teach images' times and odometry.
void ReadImages(const Reader& rd, const Json& j, TeachMap* map) {
  const Json& images = rd.Key(j, "images", "");
  const std::int64_t image_count = rd.Integer(rd.Key(images, "count", "images"), "images.count");
  if (image_count < 0) rd.Fail("images.count", "must be >= 0");
  const Json& times = rd.Array(rd.Key(images, "t_s", "images"), "images.t_s",
                               static_cast<std::size_t>(image_count));
  const Json& odometry = rd.Array(rd.Key(images, "odometry", "images"), "images.odometry",
                                  static_cast<std::size_t>(image_count));
  map->images.resize(static_cast<std::size_t>(image_count));
  for (std::size_t i = 0; i < map->images.size(); ++i) {
    map->images[i].t_s = rd.Number(times[i], Reader::Index("images.t_s", i));
    map->images[i].odometry = rd.Odometry(odometry[i], Reader::Index("images.odometry", i));
  }
}

/// Milestone `mj`'s (at `path`) images, times, cut and reconstruction; `previous` is the
/// milestone before it (nullptr for the first), `image_count` the map's teach images.
void ReadMilestoneFields(const Reader& rd, const Json& mj, const std::string& path,
                         const Milestone* previous, std::int64_t image_count, Milestone* m) {
  m->first_image =
      static_cast<int>(rd.Integer(rd.Key(mj, "first_image", path), path + ".first_image"));
  m->last_image =
      static_cast<int>(rd.Integer(rd.Key(mj, "last_image", path), path + ".last_image"));
  if (m->first_image < 0 || m->first_image >= m->last_image || m->last_image >= image_count) {
    rd.Fail(path, "needs 0 <= first_image < last_image < images.count (got " +
                      std::to_string(m->first_image) + ", " + std::to_string(m->last_image) + ")");
  }
  if (previous != nullptr && m->first_image < previous->last_image) {
    rd.Fail(path + ".first_image", "starts before the previous milestone ends");
  }
  m->first_t_s = rd.Number(rd.Key(mj, "first_t_s", path), path + ".first_t_s");
  m->last_t_s = rd.Number(rd.Key(mj, "last_t_s", path), path + ".last_t_s");
  try {
    m->cut = ParseMilestoneCut(rd.String(rd.Key(mj, "cut", path), path + ".cut"));
  } catch (const std::invalid_argument& e) {
    rd.Fail(path + ".cut", e.what());
  }
  m->reconstructed = rd.Boolean(rd.Key(mj, "reconstructed", path), path + ".reconstructed");
  const Json& T = rd.Array(rd.Key(mj, "T_first_last", path), path + ".T_first_last", 12);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      m->T_first_last.matrix()(r, c) =
          rd.Number(T[static_cast<std::size_t>(4 * r + c)],
                    Reader::Index(path + ".T_first_last", static_cast<std::size_t>(4 * r + c)));
    }
  }
  m->reprojection_error_px =
      rd.Number(rd.Key(mj, "reprojection_error_px", path), path + ".reprojection_error_px");
  m->baseline_m = rd.Number(rd.Key(mj, "baseline_m", path), path + ".baseline_m");
}

/// Milestone `mj`'s (at `path`) features: positions and 3-D points (patches come from
/// the patch file).
void ReadMilestoneFeatures(const Reader& rd, const Json& mj, const std::string& path,
                           Milestone* m) {
  const std::int64_t count = rd.Integer(rd.Key(mj, "feature_count", path), path + ".feature_count");
  const Json& features = rd.Array(rd.Key(mj, "features", path), path + ".features");
  if (count < 0 || static_cast<std::size_t>(count) != features.size()) {
    rd.Fail(path, "inconsistent counts: feature_count is " + std::to_string(count) + " but " +
                      std::to_string(features.size()) + " features are listed");
  }
  m->features.resize(features.size());
  for (std::size_t i = 0; i < features.size(); ++i) {
    const std::string fpath = Reader::Index(path + ".features", i);
    const Json& f = rd.Array(features[i], fpath, 7);
    double v[7];
    for (std::size_t c = 0; c < 7; ++c) v[c] = rd.Number(f[c], Reader::Index(fpath, c));
    m->features[i].first_px = {static_cast<float>(v[0]), static_cast<float>(v[1])};
    m->features[i].last_px = {static_cast<float>(v[2]), static_cast<float>(v[3])};
    m->features[i].p_first = {v[4], v[5], v[6]};
  }
}

/// Milestone `mj`'s (at `path`) key image, from the file map.json names below `root`: an
/// 8-bit grey PNG of the camera's size.
cv::Mat ReadKeyImage(const Reader& rd, const Json& mj, const std::string& path,
                     const fs::path& root, const CameraIntrinsics& camera) {
  const std::string key_name = rd.String(rd.Key(mj, "key_image", path), path + ".key_image");
  const fs::path key_path = root / key_name;
  const std::optional<std::string> png = ReadFile(key_path);
  if (!png) {
    throw std::runtime_error("LoadTeachMap: " + key_path.string() + ": key image of " + path +
                             " missing or unreadable");
  }
  // A PNG starts with its 8-byte signature and ends with the IEND chunk; checking both
  // reports a truncated file as such (and keeps libpng from complaining on stderr).
  static const std::string kPngSignature("\x89PNG\r\n\x1a\n", 8);
  static const std::string kPngEnd("IEND\xae\x42\x60\x82", 8);
  if (png->size() < 20 || png->compare(0, 8, kPngSignature) != 0 ||
      png->compare(png->size() - 8, 8, kPngEnd) != 0) {
    throw std::runtime_error("LoadTeachMap: " + key_path.string() +
                             ": not a decodable image (not a complete PNG file: truncated?)");
  }
  const std::vector<unsigned char> bytes(png->begin(), png->end());
  cv::Mat image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  if (image.empty()) {
    throw std::runtime_error("LoadTeachMap: " + key_path.string() +
                             ": not a decodable image (truncated?)");
  }
  if (image.type() != CV_8UC1 || image.size() != camera.size()) {
    throw std::runtime_error("LoadTeachMap: " + key_path.string() +
                             ": expected an 8-bit grey image of " + std::to_string(camera.width) +
                             "x" + std::to_string(camera.height) + " px (the camera's size)");
  }
  return image;
}

/// Every milestone, its features and key image (images below `root`). Returns the number
/// of features over all milestones.
std::size_t ReadMilestones(const Reader& rd, const Json& j, const fs::path& root, TeachMap* map) {
  const Json& milestones = rd.Array(rd.Key(j, "milestones", ""), "milestones");
  map->milestones.resize(milestones.size());
  const std::int64_t image_count = static_cast<std::int64_t>(map->images.size());
  std::size_t total_features = 0;
  for (std::size_t k = 0; k < milestones.size(); ++k) {
    const Json& mj = milestones[k];
    const std::string path = Reader::Index("milestones", k);
    Milestone& m = map->milestones[k];
    ReadMilestoneFields(rd, mj, path, k > 0 ? &map->milestones[k - 1] : nullptr, image_count, &m);
    ReadMilestoneFeatures(rd, mj, path, &m);
    total_features += m.features.size();
    m.key_image = ReadKeyImage(rd, mj, path, root, map->camera);
  }
  return total_features;
}

/// The patch file map.json names (below `root`), checked against map.json's patch count
/// and patch size and against `total_features`. Returns its bytes.
std::string ReadPatchFile(const Reader& rd, const Json& j, const fs::path& root,
                          std::size_t total_features, int patch_size_px) {
  const std::string patch_name = rd.String(rd.Key(j, "patches_file", ""), "patches_file");
  const std::int64_t patch_count = rd.Integer(rd.Key(j, "patch_count", ""), "patch_count");
  if (patch_count < 0 || static_cast<std::size_t>(patch_count) != total_features) {
    rd.Fail("patch_count", "inconsistent counts: " + std::to_string(patch_count) + " patches for " +
                               std::to_string(total_features) + " features");
  }
  const fs::path patch_path = root / patch_name;
  std::optional<std::string> blob = ReadFile(patch_path);
  const std::string pfile = "LoadTeachMap: " + patch_path.string() + ": ";
  if (!blob) throw std::runtime_error(pfile + "missing or unreadable");
  if (blob->size() < kPatchHeaderBytes || blob->compare(0, 8, kPatchMagic, 8) != 0) {
    throw std::runtime_error(pfile + "not a trackbed patch file (bad magic or truncated header)");
  }
  const std::uint64_t side = GetUint(*blob, 8, 4);
  const std::uint64_t count = GetUint(*blob, 16, 8);
  if (side != static_cast<std::uint64_t>(patch_size_px)) {
    throw std::runtime_error(pfile + "patch side " + std::to_string(side) +
                             " px, but map.json says " + std::to_string(patch_size_px));
  }
  if (count != total_features) {
    throw std::runtime_error(pfile + "inconsistent counts: holds " + std::to_string(count) +
                             " patches, map.json lists " + std::to_string(total_features) +
                             " features");
  }
  const std::uint64_t expected = kPatchHeaderBytes + count * side * side;
  if (blob->size() != expected) {
    throw std::runtime_error(pfile + (blob->size() < expected ? "truncated" : "trailing bytes") +
                             ": " + std::to_string(blob->size()) + " bytes, expected " +
                             std::to_string(expected));
  }
  return std::move(*blob);
}

/// Hands the patches of a checked patch file (ReadPatchFile) to the features, milestone
/// by milestone, feature by feature.
void AssignPatches(const std::string& blob, TeachMap* map) {
  const std::size_t side = static_cast<std::size_t>(map->patch_size_px);
  std::size_t offset = kPatchHeaderBytes;
  const int s = map->patch_size_px;
  for (Milestone& m : map->milestones) {
    for (MilestoneFeature& f : m.features) {
      f.patch.create(s, s, CV_8UC1);
      for (int r = 0; r < s; ++r) {
        std::copy(blob.begin() + static_cast<std::ptrdiff_t>(offset),
                  blob.begin() + static_cast<std::ptrdiff_t>(offset + side),
                  reinterpret_cast<char*>(f.patch.ptr<unsigned char>(r)));
        offset += side;
      }
    }
  }
}

}  // namespace

TeachMap LoadTeachMap(const std::string& dir) {
  const fs::path root(dir);
  if (!fs::is_directory(root)) {
    throw std::runtime_error("LoadTeachMap: " + dir + ": no such directory");
  }
  const fs::path map_path = root / kMapFile;
  const Reader rd(map_path.string());
  const Json j = ReadMapJson(map_path, rd);
  CheckFormat(rd, j);
  TeachMap map;
  ReadModeCameraAndPatchSize(rd, j, &map);
  ReadImages(rd, j, &map);
  const std::size_t total_features = ReadMilestones(rd, j, root, &map);
  AssignPatches(ReadPatchFile(rd, j, root, total_features, map.patch_size_px), &map);
  try {
    map.Validate();
  } catch (const std::invalid_argument& e) {
    rd.Fail("", e.what());
  }
  return map;
}

}  // namespace trackbed::teach_repeat
