// SHA-256 (FIPS 180-4) of bytes and of files: the fingerprints a run folder keeps of
// the files its scenario names (docs/run_folder.md, `inputs.json`).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace trackbed {

/// An incremental SHA-256: Add the bytes in any pieces, then HexDigest once.
class Sha256 {
 public:
  Sha256();
  void Add(const void* data, std::size_t size);
  /// The digest of everything added, as 64 lower-case hexadecimal digits.
  std::string HexDigest();

 private:
  void Block(const std::uint8_t* block);

  std::array<std::uint32_t, 8> state_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_ = 0;  // bytes added
};

/// The SHA-256 of a file's bytes. Throws std::runtime_error naming the file if it
/// cannot be read.
std::string Sha256OfFile(const std::filesystem::path& file);

}  // namespace trackbed
