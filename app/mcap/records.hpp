#pragma once
// The records of the MCAP file format (docs/specification of github.com/foxglove/mcap), named
// and ordered as the specification's tables. Every record is serialised as
// <opcode u8><content length u64><content>; integers are little-endian, a String is a u32 byte
// length and UTF-8 bytes, a Map and an Array are a u32 byte length and their entries.

#include <concepts>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace avk::app::mcap {

enum class Opcode : std::uint8_t {
  header = 0x01,
  footer,
  schema,
  channel,
  message,
  chunk,
  message_index,
  chunk_index,
  attachment,
  attachment_index,
  statistics,
  metadata,
  metadata_index,
  summary_offset,
  data_end,
};

// 0x89 "MCAP" major version '0' "\r\n", at the start and the end of every file.
inline constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};
// Opcode and content length in front of every record's content.
inline constexpr std::uint64_t kRecordPrefixBytes = 1 + 8;

struct HeaderRecord {
  static constexpr Opcode opcode = Opcode::header;
  std::string profile;
  std::string library;
};

struct FooterRecord {
  static constexpr Opcode opcode = Opcode::footer;
  std::uint64_t summary_start = 0;         // 0: no summary section
  std::uint64_t summary_offset_start = 0;  // 0: no Summary Offset records
  std::uint32_t summary_crc = 0;           // 0: not available
};

struct SchemaRecord {
  static constexpr Opcode opcode = Opcode::schema;
  std::uint16_t id = 0;  // never 0 in a valid file
  std::string name;
  std::string encoding;  // e.g. "jsonschema"; "" = no schema
  std::string data;      // u32-length-prefixed bytes

  bool operator==(const SchemaRecord&) const = default;
};

struct ChannelRecord {
  static constexpr Opcode opcode = Opcode::channel;
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;  // e.g. "json"
  std::map<std::string, std::string> metadata;

  bool operator==(const ChannelRecord&) const = default;
};

struct MessageRecord {
  static constexpr Opcode opcode = Opcode::message;
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time_ns = 0;
  std::uint64_t publish_time_ns = 0;
  std::string data;  // the rest of the record: no length prefix
};

// `records` views the bytes the chunk was parsed from or is written from.
struct ChunkRecord {
  static constexpr Opcode opcode = Opcode::chunk;
  std::uint64_t message_start_time_ns = 0;
  std::uint64_t message_end_time_ns = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;  // 0: not checked
  std::string compression;             // "" or "zstd" (or "lz4", which this station does not read)
  std::string_view records;            // u64-length-prefixed
};

struct MessageIndexEntry {
  std::uint64_t log_time_ns = 0;
  std::uint64_t offset = 0;  // from the start of the uncompressed chunk records
};

struct MessageIndexRecord {
  static constexpr Opcode opcode = Opcode::message_index;
  std::uint16_t channel_id = 0;
  std::vector<MessageIndexEntry> records;  // Array<Tuple<Timestamp, uint64>>
};

struct ChunkIndexRecord {
  static constexpr Opcode opcode = Opcode::chunk_index;
  std::uint64_t message_start_time_ns = 0;
  std::uint64_t message_end_time_ns = 0;
  std::uint64_t chunk_start_offset = 0;
  std::uint64_t chunk_length = 0;  // whole record, prefix included
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
};

struct StatisticsRecord {
  static constexpr Opcode opcode = Opcode::statistics;
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time_ns = 0;
  std::uint64_t message_end_time_ns = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;

  bool operator==(const StatisticsRecord&) const = default;
};

// The specification calls the map `metadata`; `entries` keeps it apart from the record's name.
struct MetadataRecord {
  static constexpr Opcode opcode = Opcode::metadata;
  std::string name;
  std::map<std::string, std::string> entries;

  bool operator==(const MetadataRecord&) const = default;
};

struct MetadataIndexRecord {
  static constexpr Opcode opcode = Opcode::metadata_index;
  std::uint64_t offset = 0;
  std::uint64_t length = 0;  // whole record, prefix included
  std::string name;
};

struct SummaryOffsetRecord {
  static constexpr Opcode opcode = Opcode::summary_offset;
  Opcode group_opcode = Opcode::header;
  std::uint64_t group_start = 0;
  std::uint64_t group_length = 0;
};

struct DataEndRecord {
  static constexpr Opcode opcode = Opcode::data_end;
  std::uint32_t data_section_crc = 0;  // 0: not available
};

// Each record's fields in file order, once for the writer and the reader: `v` is called with
// each field (a const one when writing) and its name in the specification.
template <class R, class Record>
concept RecordOf = std::same_as<std::remove_const_t<R>, Record>;

template <class V, RecordOf<HeaderRecord> R>
void fields(V& v, R& r) {
  v.string(r.profile, "profile");
  v.string(r.library, "library");
}
template <class V, RecordOf<FooterRecord> R>
void fields(V& v, R& r) {
  v.u64(r.summary_start, "summary_start");
  v.u64(r.summary_offset_start, "summary_offset_start");
  v.u32(r.summary_crc, "summary_crc");
}
template <class V, RecordOf<SchemaRecord> R>
void fields(V& v, R& r) {
  v.u16(r.id, "id");
  v.string(r.name, "name");
  v.string(r.encoding, "encoding");
  v.string(r.data, "data");
}
template <class V, RecordOf<ChannelRecord> R>
void fields(V& v, R& r) {
  v.u16(r.id, "id");
  v.u16(r.schema_id, "schema_id");
  v.string(r.topic, "topic");
  v.string(r.message_encoding, "message_encoding");
  v.string_map(r.metadata, "metadata");
}
template <class V, RecordOf<MessageRecord> R>
void fields(V& v, R& r) {
  v.u16(r.channel_id, "channel_id");
  v.u32(r.sequence, "sequence");
  v.u64(r.log_time_ns, "log_time");
  v.u64(r.publish_time_ns, "publish_time");
  v.rest(r.data, "data");
}
template <class V, RecordOf<ChunkRecord> R>
void fields(V& v, R& r) {
  v.u64(r.message_start_time_ns, "message_start_time");
  v.u64(r.message_end_time_ns, "message_end_time");
  v.u64(r.uncompressed_size, "uncompressed_size");
  v.u32(r.uncompressed_crc, "uncompressed_crc");
  v.string(r.compression, "compression");
  v.u64_bytes(r.records, "records");
}
template <class V, RecordOf<MessageIndexRecord> R>
void fields(V& v, R& r) {
  v.u16(r.channel_id, "channel_id");
  v.index_entries(r.records, "records");
}
template <class V, RecordOf<ChunkIndexRecord> R>
void fields(V& v, R& r) {
  v.u64(r.message_start_time_ns, "message_start_time");
  v.u64(r.message_end_time_ns, "message_end_time");
  v.u64(r.chunk_start_offset, "chunk_start_offset");
  v.u64(r.chunk_length, "chunk_length");
  v.u16_u64_map(r.message_index_offsets, "message_index_offsets");
  v.u64(r.message_index_length, "message_index_length");
  v.string(r.compression, "compression");
  v.u64(r.compressed_size, "compressed_size");
  v.u64(r.uncompressed_size, "uncompressed_size");
}
template <class V, RecordOf<StatisticsRecord> R>
void fields(V& v, R& r) {
  v.u64(r.message_count, "message_count");
  v.u16(r.schema_count, "schema_count");
  v.u32(r.channel_count, "channel_count");
  v.u32(r.attachment_count, "attachment_count");
  v.u32(r.metadata_count, "metadata_count");
  v.u32(r.chunk_count, "chunk_count");
  v.u64(r.message_start_time_ns, "message_start_time");
  v.u64(r.message_end_time_ns, "message_end_time");
  v.u16_u64_map(r.channel_message_counts, "channel_message_counts");
}
template <class V, RecordOf<MetadataRecord> R>
void fields(V& v, R& r) {
  v.string(r.name, "name");
  v.string_map(r.entries, "metadata");
}
template <class V, RecordOf<MetadataIndexRecord> R>
void fields(V& v, R& r) {
  v.u64(r.offset, "offset");
  v.u64(r.length, "length");
  v.string(r.name, "name");
}
template <class V, RecordOf<SummaryOffsetRecord> R>
void fields(V& v, R& r) {
  v.opcode(r.group_opcode, "group_opcode");
  v.u64(r.group_start, "group_start");
  v.u64(r.group_length, "group_length");
}
template <class V, RecordOf<DataEndRecord> R>
void fields(V& v, R& r) {
  v.u32(r.data_section_crc, "data_section_crc");
}

// zlib's CRC-32, as the Chunk, Data End and Footer CRCs use it (defined in app/mcap/writer.cpp).
std::uint32_t crc32(std::string_view bytes);

}  // namespace avk::app::mcap
