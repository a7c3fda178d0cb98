// The teach map's binary files (teach_map.h has their layout): features.bin and
// patches.bin, written from a map and read into one, and whole files read and written.
// Internal to teach_repeat's map reader and writer (teach_map.cpp).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "trackbed/teach_repeat/teach_map.h"

namespace trackbed::teach_repeat {

inline constexpr char kPatchFileName[] = "patches.bin";
inline constexpr char kFeatureFileName[] = "features.bin";

/// Writes `bytes` to `path`; errors begin with `who` (the public function writing).
void WriteFile(const std::filesystem::path& path, const std::string& bytes,
               const char* who = "SaveTeachMap");
/// The bytes of `path`; nothing when it cannot be opened.
std::optional<std::string> ReadFile(const std::filesystem::path& path);

/// features.bin's bytes: every feature's positions and point, milestone by milestone.
std::string FeatureBlob(const TeachMap& map);
/// patches.bin's bytes: every feature's patch, milestone by milestone.
std::string PatchBlob(const TeachMap& map);

/// The patch file at `path`, checked against the map's patch size and the
/// `total_features` map.json counts. Throws std::runtime_error naming the file.
std::string ReadPatchFile(const std::filesystem::path& path, std::size_t total_features,
                          int patch_size_px);
/// The feature file at `path`, checked against the `total_features` map.json counts.
/// Throws std::runtime_error naming the file.
std::string ReadFeatureFile(const std::filesystem::path& path, std::size_t total_features);

/// Hands the features of a checked feature file to the milestones, `counts[k]` to
/// milestone k.
void AssignFeatures(const std::string& blob, const std::vector<std::size_t>& counts, TeachMap* map);
/// Hands the patches of a checked patch file to the features, milestone by milestone,
/// feature by feature.
void AssignPatches(const std::string& blob, TeachMap* map);

}  // namespace trackbed::teach_repeat
