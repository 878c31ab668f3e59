#pragma once
// The records of the MCAP file format (docs/specification of github.com/foxglove/mcap), named
// and ordered as the specification's tables. Every record is serialised as
// <opcode u8><content length u64><content>; integers are little-endian, a String is a u32 byte
// length and UTF-8 bytes, a Map and an Array are a u32 byte length and their entries.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
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
  std::string profile;
  std::string library;
};

struct FooterRecord {
  std::uint64_t summary_start = 0;         // 0: no summary section
  std::uint64_t summary_offset_start = 0;  // 0: no Summary Offset records
  std::uint32_t summary_crc = 0;           // 0: not available
};

struct SchemaRecord {
  std::uint16_t id = 0;  // never 0 in a valid file
  std::string name;
  std::string encoding;  // e.g. "jsonschema"; "" = no schema
  std::string data;      // u32-length-prefixed bytes

  bool operator==(const SchemaRecord&) const = default;
};

struct ChannelRecord {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;  // e.g. "json"
  std::map<std::string, std::string> metadata;

  bool operator==(const ChannelRecord&) const = default;
};

struct MessageRecord {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time_ns = 0;
  std::uint64_t publish_time_ns = 0;
  std::string data;  // the rest of the record: no length prefix
};

// `records` views the bytes the chunk was parsed from or is written from.
struct ChunkRecord {
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
  std::uint16_t channel_id = 0;
  std::vector<MessageIndexEntry> records;  // Array<Tuple<Timestamp, uint64>>
};

struct ChunkIndexRecord {
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
  std::string name;
  std::map<std::string, std::string> entries;

  bool operator==(const MetadataRecord&) const = default;
};

struct MetadataIndexRecord {
  std::uint64_t offset = 0;
  std::uint64_t length = 0;  // whole record, prefix included
  std::string name;
};

struct SummaryOffsetRecord {
  Opcode group_opcode = Opcode::header;
  std::uint64_t group_start = 0;
  std::uint64_t group_length = 0;
};

struct DataEndRecord {
  std::uint32_t data_section_crc = 0;  // 0: not available
};

// zlib's CRC-32, as the Chunk, Data End and Footer CRCs use it (defined in mcap_writer.cpp).
std::uint32_t crc32(std::string_view bytes);

}  // namespace avk::app::mcap
