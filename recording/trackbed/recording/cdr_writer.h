// The CDR encoding ROS 2 messages travel in (OMG CDR, little-endian, as rmw_fastrtps
// and rosbag2 store them): a 4-byte encapsulation header (0x00 0x01 0x00 0x00, CDR_LE),
// then each field aligned to its own size (8 at most) from the end of that header;
// strings as a uint32 length counting a terminating NUL, the bytes and the NUL;
// sequences as a uint32 count and the elements; fixed arrays as the elements alone.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace trackbed::recording {

class CdrWriter {
 public:
  CdrWriter() : bytes_{0x00, 0x01, 0x00, 0x00} {}

  CdrWriter& Bool(bool v) { return Put<std::uint8_t>(v ? 1 : 0); }
  CdrWriter& UInt8(std::uint8_t v) { return Put(v); }
  CdrWriter& Int32(std::int32_t v) { return Put(v); }
  CdrWriter& UInt32(std::uint32_t v) { return Put(v); }
  CdrWriter& Float32(float v) { return Put(v); }
  CdrWriter& Float64(double v) { return Put(v); }
  CdrWriter& String(const std::string& s) {
    UInt32(static_cast<std::uint32_t>(s.size() + 1));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
    return *this;
  }
  /// A fixed-size array (`float64[9]`): the elements alone.
  template <typename T>
  CdrWriter& Array(const T* values, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) Put(values[i]);
    return *this;
  }
  /// An unbounded sequence (`float64[]`): a uint32 count, then the elements.
  template <typename T>
  CdrWriter& Sequence(const std::vector<T>& values) {
    UInt32(static_cast<std::uint32_t>(values.size()));
    return Array(values.data(), values.size());
  }
  CdrWriter& Strings(const std::vector<std::string>& values) {
    UInt32(static_cast<std::uint32_t>(values.size()));
    for (const std::string& s : values) String(s);
    return *this;
  }
  CdrWriter& Bytes(const std::vector<std::uint8_t>& values) {
    UInt32(static_cast<std::uint32_t>(values.size()));
    bytes_.insert(bytes_.end(), values.begin(), values.end());
    return *this;
  }

  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::vector<std::uint8_t> Take() { return std::move(bytes_); }

 private:
  template <typename T>
  CdrWriter& Put(T v) {
    static_assert(sizeof(T) <= 8, "CDR primitives are at most 8 bytes");
    while ((bytes_.size() - 4) % sizeof(T) != 0) bytes_.push_back(0);
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    // Little-endian whatever the host (CDR_LE in the header says so).
    const std::uint16_t probe = 1;
    const bool little = *reinterpret_cast<const unsigned char*>(&probe) == 1;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      bytes_.push_back(raw[little ? i : sizeof(T) - 1 - i]);
    }
    return *this;
  }

  std::vector<std::uint8_t> bytes_;
};

}  // namespace trackbed::recording
