#pragma once
// Writes an MCAP file: Magic, Header, chunks of messages (each followed by its Message Index
// records), Metadata, Data End, then a summary section (Schema, Channel, Statistics, Chunk Index,
// Metadata Index groups), Summary Offset records, Footer and Magic, so that viewers can seek by
// time without reading the data section. In memory, or handed to a sink as each chunk closes, so
// that a long mission's file is never held whole.

#include <boost/crc.hpp>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/mcap/records.hpp"

namespace avk::app::mcap {

enum class Compression { none, zstd };
// As written in a Chunk's compression field: "" for none, "zstd".
const char* to_string(Compression c);

struct WriterOptions {
  Compression compression = Compression::zstd;
  std::size_t chunk_size_bytes = std::size_t{1} << 20;  // uncompressed records per chunk
  std::string profile;                                  // Header.profile ("" = none)
  std::string library = "avk-station";
};

class Writer {
 public:
  // Takes the file's bytes in order; what it throws leaves the writer unusable.
  using Sink = std::function<void(std::string_view)>;

  // Without a sink the file is kept in memory and finish() returns it.
  explicit Writer(WriterOptions options = {}, Sink sink = {});

  // Ids are assigned from 1 in call order. Schema encoding e.g. "jsonschema"; data = schema text.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           std::string_view data);
  // schema_id 0 = no schema. Throws std::invalid_argument on an unknown schema id.
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  // Messages in log-time order: a log_time_ns earlier than the previous message's throws
  // std::invalid_argument naming both times. Sequence numbers count per channel from 1.
  void add_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                   std::uint64_t publish_time_ns, std::string_view data);
  void add_metadata(const std::string& name, const std::map<std::string, std::string>& entries);
  // Closes the last chunk, writes the summary section, the footer (with summary CRC) and the
  // magic; returns the whole file (empty with a sink, which has had it all). The writer takes
  // nothing afterwards (std::logic_error).
  std::string finish();

 private:
  void check_open() const;
  // Where the next byte lands in the file.
  std::uint64_t offset() const { return flushed_ + out_.size(); }
  // With a sink: hands it what out_ holds (data-section bytes count into the Data End CRC).
  void flush();
  void write_definitions_into_chunk(std::uint16_t channel_id);
  void close_chunk();

  WriterOptions options_;
  Sink sink_;
  // The file so far, less what went to the sink (flushed_ bytes); the open chunk is kept apart
  // until it closes.
  std::string out_;
  std::uint64_t flushed_ = 0;
  boost::crc_32_type data_crc_;  // of the data-section bytes flushed
  std::vector<SchemaRecord> schemas_;
  std::vector<ChannelRecord> channels_;
  std::vector<bool> schema_written_;   // by id - 1: already in the data section
  std::vector<bool> channel_written_;  // by id - 1
  std::vector<std::uint32_t> sequences_;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts_;

  // The open chunk: its uncompressed records and the index of its messages.
  std::string chunk_records_;
  std::uint64_t chunk_start_time_ns_ = 0;
  std::uint64_t chunk_end_time_ns_ = 0;
  std::map<std::uint16_t, std::vector<MessageIndexEntry>> chunk_message_index_;

  std::vector<ChunkIndexRecord> chunk_indexes_;
  std::vector<MetadataIndexRecord> metadata_indexes_;
  std::optional<std::uint64_t> first_log_time_ns_;
  std::uint64_t last_log_time_ns_ = 0;
  std::uint64_t message_count_ = 0;
  bool finished_ = false;
};

}  // namespace avk::app::mcap
