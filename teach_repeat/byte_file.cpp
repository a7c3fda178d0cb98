// Bytes in files (see byte_file.h).
#include "byte_file.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace trackbed::teach_repeat {

namespace fs = std::filesystem;

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

}  // namespace trackbed::teach_repeat
