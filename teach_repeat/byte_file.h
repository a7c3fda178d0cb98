// Bytes in files, for the teach map's binary files (teach_map.cpp): whole files written
// and read, and numbers put into and got from byte strings little endian, whatever the
// host's byte order (IEEE 754 numbers by their bits).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace trackbed::teach_repeat {

/// Writes `bytes` to `path`; errors (std::runtime_error) begin with `who`, the public
/// function writing.
void WriteFile(const std::filesystem::path& path, const std::string& bytes,
               const char* who = "SaveTeachMap");
/// The bytes of `path`; nothing when it cannot be opened.
std::optional<std::string> ReadFile(const std::filesystem::path& path);

/// Appends the low `bytes` bytes of `value`, least significant first.
void PutUint(std::string* out, std::uint64_t value, int bytes);
/// The `bytes`-byte little-endian integer at `offset` of `in` (which must hold it).
std::uint64_t GetUint(const std::string& in, std::size_t offset, int bytes);
void PutFloat(std::string* out, float value);
void PutDouble(std::string* out, double value);
float GetFloat(const std::string& in, std::size_t offset);
double GetDouble(const std::string& in, std::size_t offset);

}  // namespace trackbed::teach_repeat
