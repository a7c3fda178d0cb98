// The teach map's files of features, features.bin and patches.bin (their layout is in
// teach_map.h): records written, files checked, and read whole or one milestone's span
// at a time. Errors name the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "trackbed/teach_repeat/milestone_feature.h"

namespace trackbed::teach_repeat {

// The header of both files: magic, uint32 field, uint32 0, uint64 count.
inline constexpr std::size_t kRecordHeaderBytes = 8 + 4 + 4 + 8;
// One feature in features.bin: first_px, last_px (4 float32), p_first (3 float64).
inline constexpr std::size_t kFeatureRecordBytes = 4 * 4 + 3 * 8;

/// The header of features.bin for `count` features.
std::string FeatureFileHeader(std::uint64_t count);
/// The header of patches.bin for `count` patches of `side` × `side` px.
std::string PatchFileHeader(int side, std::uint64_t count);
/// Appends `f`'s record of features.bin.
void PutFeature(const MilestoneFeature& f, std::string* out);
/// Appends `f`'s patch, `side` × `side` px, row by row.
void PutPatch(const MilestoneFeature& f, int side, std::string* out);

/// The feature file at `path` read whole and checked: its magic, record size, count
/// (against `total`, the features map.json counts) and size. Errors begin "LoadTeachMap: ".
std::string ReadFeatureFile(const std::filesystem::path& path, std::uint64_t total);
/// The patch file, the same, its patches `side` px.
std::string ReadPatchFile(const std::filesystem::path& path, std::uint64_t total, int side);
/// The same checks as the two above, from the file's header and size only.
void CheckFeatureFile(const std::filesystem::path& path, std::uint64_t total);
void CheckPatchFile(const std::filesystem::path& path, std::uint64_t total, int side);

/// Sets the positions and points of every one of `*features` from the records at `offset`
/// of `bytes` (which must hold them); returns the offset after them.
std::size_t GetFeatures(const std::string& bytes, std::size_t offset,
                        std::vector<MilestoneFeature>* features);
/// Sets the patch of every one of `*features`, `side` px, from `offset` of `bytes`;
/// returns the offset after them.
std::size_t GetPatches(const std::string& bytes, std::size_t offset, int side,
                       std::vector<MilestoneFeature>* features);

/// Records [first, first + count) of `record_bytes` each of the feature or patch file at
/// `path`. Throws std::runtime_error beginning with `who` and naming the file when it
/// cannot be read or is shorter.
std::string ReadRecords(const std::filesystem::path& path, std::uint64_t first, std::uint64_t count,
                        std::uint64_t record_bytes, const char* who);

/// Writes `records` (whole records of `record_bytes`) into the feature or patch file at
/// `path` after its first `first` records, and `header` (the header counting them all)
/// at its start; the file is created anew when `first` is 0. Throws std::runtime_error
/// beginning with `who` and naming the file when it cannot be written or holds fewer
/// than `first` records.
void WriteRecordsAt(const std::filesystem::path& path, const std::string& header,
                    std::uint64_t first, std::uint64_t record_bytes, const std::string& records,
                    const char* who);

}  // namespace trackbed::teach_repeat
