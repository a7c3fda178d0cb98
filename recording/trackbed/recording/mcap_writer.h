// An MCAP file writer, from the published specification (mcap.dev/spec, format version
// 0): the magic, a Header, Schema and Channel records, Messages in zstd-compressed
// Chunks each followed by its MessageIndex records, DataEnd with the data section's
// CRC-32, a summary section (Schemas, Channels, Statistics, ChunkIndexes, grouped by
// SummaryOffset records) and the Footer with the summary's CRC-32, so that a reader can
// seek by time and channel without scanning. Records are written as they fill a chunk:
// a run that stops before Close() leaves the chunks written so far, which a recovering
// reader (`mcap recover`) can read. The bytes depend only on the calls made (no clock,
// no host name): the same run gives the same file.
#pragma once

#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace trackbed::recording {

struct McapOptions {
  std::string profile = "ros2";      ///< the Header's profile
  std::string library = "trackbed";  ///< the Header's library
  /// A chunk is closed once its uncompressed records reach this size [bytes].
  std::size_t chunk_size_bytes = 1 << 20;
  int zstd_level = 3;  ///< zstd's default level
};

class McapWriter {
 public:
  /// Creates (truncates) `path` and writes the magic and the Header. Throws
  /// std::runtime_error naming the file when it cannot be written.
  McapWriter(std::string path, McapOptions options = {});
  /// Closes the file if Close() was not called (errors then go unreported).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Registers a schema (`encoding` e.g. `ros2msg`, `data` its definition text); ids
  /// count from 1.
  std::uint16_t AddSchema(const std::string& name, const std::string& encoding,
                          const std::string& data);
  /// Registers a channel on a registered schema; ids count from 0.
  std::uint16_t AddChannel(std::uint16_t schema_id, const std::string& topic,
                           const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata = {});
  /// Adds a message to the open chunk; its sequence number counts per channel from 0.
  /// Times are nanoseconds.
  void Write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
             const std::vector<std::uint8_t>& data);
  /// Writes the last chunk, DataEnd, the summary and the Footer; throws
  /// std::runtime_error when the file cannot be written.
  void Close();

  std::uint64_t message_count() const { return message_count_; }

 private:
  struct Schema {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t id, schema_id;
    std::string topic, message_encoding;
    std::map<std::string, std::string> metadata;
    std::uint32_t next_sequence = 0;
    std::uint64_t message_count = 0;
  };
  struct ChunkIndex {
    std::uint64_t start_ns, end_ns, offset, length;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length, compressed_size, uncompressed_size;
  };

  void Emit(const std::string& bytes);  // to the file, counting offset and CRCs
  void Emit(const char* bytes, std::size_t n);
  void FlushChunk();
  void WriteSummary();
  static std::string SchemaRecord(const Schema& s);
  static std::string ChannelRecord(const Channel& c);

  std::string path_;
  McapOptions options_;
  std::ofstream out_;
  bool closed_ = false;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  // The open chunk: its records uncompressed, its time span, and per channel the
  // (log time, offset in the chunk) of each message.
  std::string chunk_;
  std::uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<ChunkIndex> chunk_indexes_;
  std::uint64_t message_count_ = 0, start_ns_ = 0, end_ns_ = 0;
};

}  // namespace trackbed::recording
