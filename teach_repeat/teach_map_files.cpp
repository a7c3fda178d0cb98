// The teach map's binary files (see teach_map_files.h, teach_map.h).
#include "teach_map_files.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <utility>

namespace trackbed::teach_repeat {
namespace {

namespace fs = std::filesystem;

constexpr char kPatchMagic[8] = {'T', 'B', 'P', 'A', 'T', 'C', 'H', '1'};
// The header of patches.bin and features.bin: magic, uint32 field, uint32 0, uint64 count.
constexpr std::size_t kRecordHeaderBytes = 8 + 4 + 4 + 8;
constexpr char kFeatureMagic[8] = {'T', 'B', 'F', 'E', 'A', 'T', 'S', '1'};
// One feature in features.bin: first_px, last_px (4 float32), p_first (3 float64).
constexpr std::size_t kFeatureRecordBytes = 4 * 4 + 3 * 8;

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

// IEEE 754 numbers by their bits, little-endian as the integers.
void PutFloat(std::string* out, float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  PutUint(out, bits, 4);
}
void PutDouble(std::string* out, double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  PutUint(out, bits, 8);
}
float GetFloat(const std::string& in, std::size_t offset) {
  const auto bits = static_cast<std::uint32_t>(GetUint(in, offset, 4));
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}
double GetDouble(const std::string& in, std::size_t offset) {
  const std::uint64_t bits = GetUint(in, offset, 8);
  double value = 0.0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace

void WriteFile(const fs::path& path, const std::string& bytes, const char* who) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw std::runtime_error(std::string(who) + ": " + path.string() + ": cannot open for writing");
  }
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error(std::string(who) + ": " + path.string() + ": write failed");
}

std::optional<std::string> ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// features.bin's bytes: every feature, milestone by milestone.
std::string FeatureBlob(const TeachMap& map) {
  const std::size_t count = map.feature_count();
  std::string blob(kFeatureMagic, kFeatureMagic + 8);
  PutUint(&blob, kFeatureRecordBytes, 4);
  PutUint(&blob, 0, 4);
  PutUint(&blob, count, 8);
  blob.reserve(kRecordHeaderBytes + count * kFeatureRecordBytes);
  for (const Milestone& m : map.milestones) {
    for (const MilestoneFeature& f : m.features) {
      for (float v : {f.first_px.x, f.first_px.y, f.last_px.x, f.last_px.y}) PutFloat(&blob, v);
      for (int i = 0; i < 3; ++i) PutDouble(&blob, f.p_first[i]);
    }
  }
  return blob;
}

/// patches.bin's bytes.
std::string PatchBlob(const TeachMap& map) {
  const std::size_t count = map.feature_count();
  const std::size_t side = static_cast<std::size_t>(map.patch_size_px);
  std::string patches(kPatchMagic, kPatchMagic + 8);
  PutUint(&patches, side, 4);
  PutUint(&patches, 0, 4);
  PutUint(&patches, count, 8);
  patches.reserve(kRecordHeaderBytes + count * side * side);
  for (const Milestone& m : map.milestones) {
    for (const MilestoneFeature& f : m.features) {
      for (int r = 0; r < f.patch.rows; ++r) {
        const char* row = reinterpret_cast<const char*>(f.patch.ptr<unsigned char>(r));
        patches.append(row, side);
      }
    }
  }
  return patches;
}

namespace {

/// One of the map's binary files: its 8-byte `magic`, a uint32 header field, uint32 0 and
/// a uint64 count, then count records of `record_bytes`. Checked: the magic, the field
/// (`field_error` says what is wrong with it, or nothing), the count against the
/// `total` map.json counts, the size. Returns its bytes; errors name the file.
std::string ReadRecordFile(const fs::path& path, const char (&magic)[8], const char* kind,
                           const std::function<std::string(std::uint64_t)>& field_error,
                           std::uint64_t record_bytes, std::size_t total, const char* records) {
  std::optional<std::string> blob = ReadFile(path);
  const std::string where = "LoadTeachMap: " + path.string() + ": ";
  if (!blob) throw std::runtime_error(where + "missing or unreadable");
  if (blob->size() < kRecordHeaderBytes || blob->compare(0, 8, magic, 8) != 0) {
    throw std::runtime_error(where + "not a trackbed " + kind +
                             " file (bad magic or truncated header)");
  }
  const std::string wrong_field = field_error(GetUint(*blob, 8, 4));
  if (!wrong_field.empty()) throw std::runtime_error(where + wrong_field);
  const std::uint64_t count = GetUint(*blob, 16, 8);
  if (count != total) {
    throw std::runtime_error(where + "inconsistent counts: holds " + std::to_string(count) + " " +
                             records + ", map.json counts " + std::to_string(total) + " features");
  }
  const std::uint64_t expected = kRecordHeaderBytes + count * record_bytes;
  if (blob->size() != expected) {
    throw std::runtime_error(where + (blob->size() < expected ? "truncated" : "trailing bytes") +
                             ": " + std::to_string(blob->size()) + " bytes, expected " +
                             std::to_string(expected));
  }
  return std::move(*blob);
}

}  // namespace

/// The patch file map.json names, checked against the map's patch size and its
/// `total_features`.
std::string ReadPatchFile(const fs::path& path, std::size_t total_features, int patch_size_px) {
  const auto side = static_cast<std::uint64_t>(patch_size_px);
  return ReadRecordFile(
      path, kPatchMagic, "patch",
      [&](std::uint64_t found) {
        return found == side ? std::string()
                             : "patch side " + std::to_string(found) + " px, but map.json says " +
                                   std::to_string(patch_size_px);
      },
      side * side, total_features, "patches");
}

/// The feature file map.json names (version 2 on), checked against the features its
/// milestones count (`total_features`).
std::string ReadFeatureFile(const fs::path& path, std::size_t total_features) {
  return ReadRecordFile(
      path, kFeatureMagic, "feature",
      [](std::uint64_t found) {
        return found == kFeatureRecordBytes
                   ? std::string()
                   : "records of " + std::to_string(found) + " bytes, this build reads " +
                         std::to_string(kFeatureRecordBytes);
      },
      kFeatureRecordBytes, total_features, "features");
}

/// Hands the features of a checked feature file (ReadFeatureFile) to the milestones, as
/// many to each as map.json counts.
void AssignFeatures(const std::string& blob, const std::vector<std::size_t>& counts,
                    TeachMap* map) {
  std::size_t offset = kRecordHeaderBytes;
  for (std::size_t k = 0; k < map->milestones.size(); ++k) {
    std::vector<MilestoneFeature>& features = map->milestones[k].features;
    features.resize(counts[k]);
    for (MilestoneFeature& f : features) {
      f.first_px = {GetFloat(blob, offset), GetFloat(blob, offset + 4)};
      f.last_px = {GetFloat(blob, offset + 8), GetFloat(blob, offset + 12)};
      for (int i = 0; i < 3; ++i) f.p_first[i] = GetDouble(blob, offset + 16 + 8 * i);
      offset += kFeatureRecordBytes;
    }
  }
}

/// Hands the patches of a checked patch file (ReadPatchFile) to the features, milestone
/// by milestone, feature by feature.
void AssignPatches(const std::string& blob, TeachMap* map) {
  const std::size_t side = static_cast<std::size_t>(map->patch_size_px);
  std::size_t offset = kRecordHeaderBytes;
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

}  // namespace trackbed::teach_repeat
