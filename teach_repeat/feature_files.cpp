// The teach map's files of features (see feature_files.h).
#include "feature_files.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "byte_file.h"

namespace trackbed::teach_repeat {
namespace {

namespace fs = std::filesystem;

constexpr char kPatchMagic[8] = {'T', 'B', 'P', 'A', 'T', 'C', 'H', '1'};
constexpr char kFeatureMagic[8] = {'T', 'B', 'F', 'E', 'A', 'T', 'S', '1'};

std::string Header(const char (&magic)[8], std::uint64_t field, std::uint64_t count) {
  std::string header(magic, magic + 8);
  PutUint(&header, field, 4);
  PutUint(&header, 0, 4);
  PutUint(&header, count, 8);
  return header;
}

/// One of the two files from its `header` (its first bytes, as many as it has up to
/// kRecordHeaderBytes) and its size: the 8-byte `magic`, the uint32 field (`field_error`
/// says what is wrong with it, or nothing), the count against the `total` map.json
/// counts, the size against count records of `record_bytes`.
void CheckRecordFile(const fs::path& path, const std::string& header, std::uint64_t size,
                     const char (&magic)[8], const char* kind,
                     const std::function<std::string(std::uint64_t)>& field_error,
                     std::uint64_t record_bytes, std::uint64_t total, const char* records) {
  const std::string where = "LoadTeachMap: " + path.string() + ": ";
  if (header.size() < kRecordHeaderBytes || header.compare(0, 8, magic, 8) != 0) {
    throw std::runtime_error(where + "not a trackbed " + kind +
                             " file (bad magic or truncated header)");
  }
  const std::string wrong_field = field_error(GetUint(header, 8, 4));
  if (!wrong_field.empty()) throw std::runtime_error(where + wrong_field);
  const std::uint64_t count = GetUint(header, 16, 8);
  if (count != total) {
    throw std::runtime_error(where + "inconsistent counts: holds " + std::to_string(count) + " " +
                             records + ", map.json counts " + std::to_string(total) + " features");
  }
  const std::uint64_t expected = kRecordHeaderBytes + count * record_bytes;
  if (size != expected) {
    throw std::runtime_error(where + (size < expected ? "truncated" : "trailing bytes") + ": " +
                             std::to_string(size) + " bytes, expected " + std::to_string(expected));
  }
}

std::function<std::string(std::uint64_t)> FeatureFieldError() {
  return [](std::uint64_t found) {
    return found == kFeatureRecordBytes
               ? std::string()
               : "records of " + std::to_string(found) + " bytes, this build reads " +
                     std::to_string(kFeatureRecordBytes);
  };
}

std::function<std::string(std::uint64_t)> PatchFieldError(int side) {
  return [side](std::uint64_t found) {
    return found == static_cast<std::uint64_t>(side)
               ? std::string()
               : "patch side " + std::to_string(found) + " px, but map.json says " +
                     std::to_string(side);
  };
}

std::string ReadWhole(const fs::path& path) {
  std::optional<std::string> blob = ReadFile(path);
  if (!blob) throw std::runtime_error("LoadTeachMap: " + path.string() + ": missing or unreadable");
  return std::move(*blob);
}

// The file's header (as many of its first bytes as it has) and its size.
std::pair<std::string, std::uint64_t> HeaderAndSize(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!in || ec) {
    throw std::runtime_error("LoadTeachMap: " + path.string() + ": missing or unreadable");
  }
  std::string header(kRecordHeaderBytes, '\0');
  in.read(header.data(), static_cast<std::streamsize>(header.size()));
  header.resize(static_cast<std::size_t>(in.gcount()));
  return {header, size};
}

}  // namespace

std::string FeatureFileHeader(std::uint64_t count) {
  return Header(kFeatureMagic, kFeatureRecordBytes, count);
}

std::string PatchFileHeader(int side, std::uint64_t count) {
  return Header(kPatchMagic, static_cast<std::uint64_t>(side), count);
}

void PutFeature(const MilestoneFeature& f, std::string* out) {
  for (float v : {f.first_px.x, f.first_px.y, f.last_px.x, f.last_px.y}) PutFloat(out, v);
  for (int i = 0; i < 3; ++i) PutDouble(out, f.p_first[i]);
}

void PutPatch(const MilestoneFeature& f, int side, std::string* out) {
  for (int r = 0; r < side; ++r) {
    out->append(reinterpret_cast<const char*>(f.patch.ptr<unsigned char>(r)),
                static_cast<std::size_t>(side));
  }
}

std::string ReadFeatureFile(const fs::path& path, std::uint64_t total) {
  std::string blob = ReadWhole(path);
  CheckRecordFile(path, blob.substr(0, kRecordHeaderBytes), blob.size(), kFeatureMagic, "feature",
                  FeatureFieldError(), kFeatureRecordBytes, total, "features");
  return blob;
}

std::string ReadPatchFile(const fs::path& path, std::uint64_t total, int side) {
  std::string blob = ReadWhole(path);
  const auto s = static_cast<std::uint64_t>(side);
  CheckRecordFile(path, blob.substr(0, kRecordHeaderBytes), blob.size(), kPatchMagic, "patch",
                  PatchFieldError(side), s * s, total, "patches");
  return blob;
}

void CheckFeatureFile(const fs::path& path, std::uint64_t total) {
  const auto [header, size] = HeaderAndSize(path);
  CheckRecordFile(path, header, size, kFeatureMagic, "feature", FeatureFieldError(),
                  kFeatureRecordBytes, total, "features");
}

void CheckPatchFile(const fs::path& path, std::uint64_t total, int side) {
  const auto [header, size] = HeaderAndSize(path);
  const auto s = static_cast<std::uint64_t>(side);
  CheckRecordFile(path, header, size, kPatchMagic, "patch", PatchFieldError(side), s * s, total,
                  "patches");
}

std::size_t GetFeatures(const std::string& bytes, std::size_t offset,
                        std::vector<MilestoneFeature>* features) {
  for (MilestoneFeature& f : *features) {
    f.first_px = {GetFloat(bytes, offset), GetFloat(bytes, offset + 4)};
    f.last_px = {GetFloat(bytes, offset + 8), GetFloat(bytes, offset + 12)};
    for (int i = 0; i < 3; ++i) f.p_first[i] = GetDouble(bytes, offset + 16 + 8 * i);
    offset += kFeatureRecordBytes;
  }
  return offset;
}

std::size_t GetPatches(const std::string& bytes, std::size_t offset, int side,
                       std::vector<MilestoneFeature>* features) {
  const auto row = static_cast<std::size_t>(side);
  for (MilestoneFeature& f : *features) {
    f.patch.create(side, side, CV_8UC1);
    for (int r = 0; r < side; ++r) {
      std::copy(bytes.begin() + static_cast<std::ptrdiff_t>(offset),
                bytes.begin() + static_cast<std::ptrdiff_t>(offset + row),
                reinterpret_cast<char*>(f.patch.ptr<unsigned char>(r)));
      offset += row;
    }
  }
  return offset;
}

std::string ReadRecords(const fs::path& path, std::uint64_t first, std::uint64_t count,
                        std::uint64_t record_bytes, const char* who) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(count * record_bytes), '\0');
  in.seekg(static_cast<std::streamoff>(kRecordHeaderBytes + first * record_bytes));
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!in || static_cast<std::size_t>(in.gcount()) != bytes.size()) {
    throw std::runtime_error(std::string(who) + ": " + path.string() + ": cannot read records " +
                             std::to_string(first) + " to " + std::to_string(first + count) +
                             " (missing, unreadable or truncated)");
  }
  return bytes;
}

void WriteRecordsAt(const fs::path& path, const std::string& header, std::uint64_t first,
                    std::uint64_t record_bytes, const std::string& records, const char* who) {
  const std::string where = std::string(who) + ": " + path.string() + ": ";
  const std::uint64_t offset = kRecordHeaderBytes + first * record_bytes;
  std::error_code ec;
  if (first > 0 && !(fs::file_size(path, ec) >= offset && !ec)) {
    throw std::runtime_error(where + "missing or holds fewer than " + std::to_string(first) +
                             " records");
  }
  std::fstream out(path, first == 0 ? std::ios::binary | std::ios::out | std::ios::trunc
                                    : std::ios::binary | std::ios::in | std::ios::out);
  if (!out) throw std::runtime_error(where + "cannot open for writing");
  out.seekp(static_cast<std::streamoff>(offset));
  out.write(records.data(), static_cast<std::streamsize>(records.size()));
  out.seekp(0);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.close();
  if (!out) throw std::runtime_error(where + "write failed");
}

}  // namespace trackbed::teach_repeat
