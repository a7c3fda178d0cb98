// MCAP writer (see mcap_writer.h). Every integer is little-endian; a String is a
// uint32 byte length and the bytes; Bytes likewise; a Map or Array is a uint32 byte
// length and its entries.
#include "trackbed/recording/mcap_writer.h"

#include <zlib.h>
#include <zstd.h>

#include <memory>
#include <stdexcept>

namespace trackbed::recording {
namespace {

const char kMagic[] = "\x89MCAP0\r\n";  // 8 bytes

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// Little-endian fields appended to a byte string.
class Fields {
 public:
  Fields& U8(std::uint8_t v) { return Int(v, 1); }
  Fields& U16(std::uint16_t v) { return Int(v, 2); }
  Fields& U32(std::uint32_t v) { return Int(v, 4); }
  Fields& U64(std::uint64_t v) { return Int(v, 8); }
  Fields& Raw(const std::string& s) {
    bytes_ += s;
    return *this;
  }
  Fields& String(const std::string& s) { return U32(static_cast<std::uint32_t>(s.size())).Raw(s); }
  Fields& Prefixed32(const Fields& inner) { return String(inner.bytes_); }
  const std::string& bytes() const { return bytes_; }

 private:
  Fields& Int(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes_.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
    return *this;
  }
  std::string bytes_;
};

std::string Record(Opcode op, const Fields& content) {
  Fields r;
  r.U8(op).U64(content.bytes().size()).Raw(content.bytes());
  return r.bytes();
}

std::uint32_t Crc32(std::uint32_t crc, const std::string& bytes) {
  return static_cast<std::uint32_t>(
      crc32(crc, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

}  // namespace

McapWriter::McapWriter(std::string path, McapOptions options)
    : path_(std::move(path)), options_(std::move(options)) {
  out_.open(path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error(path_ + ": cannot open for writing");
  Emit(std::string(kMagic, 8));
  Emit(Record(kHeader, Fields().String(options_.profile).String(options_.library)));
}

McapWriter::~McapWriter() {
  if (closed_) return;
  try {
    Close();
  } catch (...) {
  }
}

void McapWriter::Emit(const std::string& bytes) { Emit(bytes.data(), bytes.size()); }

void McapWriter::Emit(const char* bytes, std::size_t n) {
  out_.write(bytes, static_cast<std::streamsize>(n));
  if (!out_) throw std::runtime_error(path_ + ": write failed");
  offset_ += n;
  data_crc_ = static_cast<std::uint32_t>(
      crc32(data_crc_, reinterpret_cast<const Bytef*>(bytes), static_cast<uInt>(n)));
}

std::string McapWriter::SchemaRecord(const Schema& s) {
  return Record(kSchema, Fields().U16(s.id).String(s.name).String(s.encoding).String(s.data));
}

std::string McapWriter::ChannelRecord(const Channel& c) {
  Fields map;
  for (const auto& [key, value] : c.metadata) map.String(key).String(value);
  return Record(kChannel, Fields()
                              .U16(c.id)
                              .U16(c.schema_id)
                              .String(c.topic)
                              .String(c.message_encoding)
                              .Prefixed32(map));
}

std::uint16_t McapWriter::AddSchema(const std::string& name, const std::string& encoding,
                                    const std::string& data) {
  if (schemas_.size() >= 0xfffe) throw std::runtime_error(path_ + ": too many schemas");
  schemas_.push_back({static_cast<std::uint16_t>(schemas_.size() + 1), name, encoding, data});
  // Outside any chunk, in the data section: a streaming reader meets it first.
  Emit(SchemaRecord(schemas_.back()));
  return schemas_.back().id;
}

std::uint16_t McapWriter::AddChannel(std::uint16_t schema_id, const std::string& topic,
                                     const std::string& message_encoding,
                                     const std::map<std::string, std::string>& metadata) {
  if (schema_id == 0 || schema_id > schemas_.size()) {
    throw std::invalid_argument(path_ + ": channel " + topic + " on an unknown schema");
  }
  if (channels_.size() >= 0xffff) throw std::runtime_error(path_ + ": too many channels");
  Channel c{static_cast<std::uint16_t>(channels_.size()), schema_id, topic, message_encoding,
            metadata};
  channels_.push_back(c);
  Emit(ChannelRecord(c));
  return c.id;
}

void McapWriter::Write(std::uint16_t channel_id, std::uint64_t log_time_ns,
                       std::uint64_t publish_time_ns, const std::vector<std::uint8_t>& data) {
  if (closed_) throw std::logic_error(path_ + ": write after Close()");
  if (channel_id >= channels_.size()) throw std::invalid_argument(path_ + ": unknown channel");
  Channel& c = channels_[channel_id];
  if (chunk_.empty()) chunk_start_ns_ = chunk_end_ns_ = log_time_ns;
  chunk_start_ns_ = std::min(chunk_start_ns_, log_time_ns);
  chunk_end_ns_ = std::max(chunk_end_ns_, log_time_ns);
  if (message_count_ == 0) start_ns_ = end_ns_ = log_time_ns;
  start_ns_ = std::min(start_ns_, log_time_ns);
  end_ns_ = std::max(end_ns_, log_time_ns);
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());
  // The record written in place (the data may be an image: no copies on the way).
  Fields head;
  head.U8(kMessage).U64(2 + 4 + 8 + 8 + data.size());
  head.U16(channel_id).U32(c.next_sequence++).U64(log_time_ns).U64(publish_time_ns);
  chunk_ += head.bytes();
  chunk_.append(reinterpret_cast<const char*>(data.data()), data.size());
  ++c.message_count;
  ++message_count_;
  if (chunk_.size() >= options_.chunk_size_bytes) FlushChunk();
}

void McapWriter::FlushChunk() {
  if (chunk_.empty()) return;
  const std::size_t bound = ZSTD_compressBound(chunk_.size());
  const std::unique_ptr<char[]> compressed(new char[bound]);
  const std::size_t n =
      ZSTD_compress(compressed.get(), bound, chunk_.data(), chunk_.size(), options_.zstd_level);
  if (ZSTD_isError(n)) throw std::runtime_error(path_ + ": zstd: " + ZSTD_getErrorName(n));
  ChunkIndex index{chunk_start_ns_, chunk_end_ns_, offset_, 0, {}, 0, n, chunk_.size()};
  Fields head;  // the Chunk record up to its compressed records, which follow as they are
  head.U8(kChunk).U64(8 + 8 + 8 + 4 + (4 + 4) + 8 + n);
  head.U64(chunk_start_ns_).U64(chunk_end_ns_).U64(chunk_.size()).U32(Crc32(0, chunk_));
  head.String("zstd").U64(n);
  Emit(head.bytes());
  Emit(compressed.get(), n);
  index.length = offset_ - index.offset;
  const std::uint64_t indexes_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    Fields array;
    for (const auto& [time, at] : entries) array.U64(time).U64(at);
    index.message_index_offsets[channel] = offset_;
    Emit(Record(kMessageIndex, Fields().U16(channel).Prefixed32(array)));
  }
  index.message_index_length = offset_ - indexes_start;
  chunk_indexes_.push_back(std::move(index));
  chunk_.clear();
  chunk_index_.clear();
  out_.flush();
}

void McapWriter::Close() {
  if (closed_) return;
  FlushChunk();
  Emit(Record(kDataEnd, Fields().U32(data_crc_)));
  WriteSummary();
  out_.close();
  closed_ = true;
  if (!out_) throw std::runtime_error(path_ + ": close failed");
}

void McapWriter::WriteSummary() {
  const std::uint64_t summary_start = offset_;
  std::uint32_t summary_crc = 0;
  const auto emit = [&](const std::string& bytes) {
    Emit(bytes);
    summary_crc = Crc32(summary_crc, bytes);
  };
  std::vector<std::string> offsets;  // SummaryOffset records, one per group
  const auto group = [&](Opcode op, const std::vector<std::string>& records) {
    if (records.empty()) return;
    const std::uint64_t start = offset_;
    for (const std::string& r : records) emit(r);
    offsets.push_back(Record(kSummaryOffset, Fields().U8(op).U64(start).U64(offset_ - start)));
  };
  std::vector<std::string> records;
  for (const Schema& s : schemas_) records.push_back(SchemaRecord(s));
  group(kSchema, records);
  records.clear();
  for (const Channel& c : channels_) records.push_back(ChannelRecord(c));
  group(kChannel, records);
  Fields counts;
  for (const Channel& c : channels_) counts.U16(c.id).U64(c.message_count);
  Fields stats;
  stats.U64(message_count_).U16(static_cast<std::uint16_t>(schemas_.size()));
  stats.U32(static_cast<std::uint32_t>(channels_.size())).U32(0).U32(0);
  stats.U32(static_cast<std::uint32_t>(chunk_indexes_.size())).U64(start_ns_).U64(end_ns_);
  stats.Prefixed32(counts);
  group(kStatistics, {Record(kStatistics, stats)});
  records.clear();
  for (const ChunkIndex& i : chunk_indexes_) {
    Fields map;
    for (const auto& [channel, at] : i.message_index_offsets) map.U16(channel).U64(at);
    Fields c;
    c.U64(i.start_ns).U64(i.end_ns).U64(i.offset).U64(i.length).Prefixed32(map);
    c.U64(i.message_index_length).String("zstd").U64(i.compressed_size).U64(i.uncompressed_size);
    records.push_back(Record(kChunkIndex, c));
  }
  group(kChunkIndex, records);
  const std::uint64_t summary_offset_start = offset_;
  for (const std::string& r : offsets) emit(r);
  // The Footer's CRC covers the summary and the Footer up to the CRC itself.
  Fields footer_head;
  footer_head.U8(kFooter).U64(8 + 8 + 4).U64(summary_start).U64(summary_offset_start);
  summary_crc = Crc32(summary_crc, footer_head.bytes());
  Emit(footer_head.bytes() + Fields().U32(summary_crc).bytes());
  Emit(std::string(kMagic, 8));
}

}  // namespace trackbed::recording
