#pragma once
// Reads MCAP files (chunks uncompressed or zstd): the station's own exports and any valid file.
// Every length is checked against the bytes that remain before anything is allocated, so a
// corrupt or hostile file gives an McapError naming what is wrong and its byte offset.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "app/mcap/records.hpp"

namespace avk::app::mcap {

class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct McapContents {
  std::string profile, library;
  std::vector<SchemaRecord> schemas;
  std::vector<ChannelRecord> channels;
  std::vector<MessageRecord> messages;  // in file order
  std::vector<MetadataRecord> metadata;
  std::optional<StatisticsRecord> statistics;
  std::size_t chunk_count = 0;
};

// How much a file may inflate to. A chunk's CRC is of its uncompressed records, so a chunk must be
// inflated whole before it can be checked: these caps are checked against the sizes the chunks
// declare, before anything is allocated or inflated (docs/foxglove.md, "Import").
struct ReadLimits {
  // The uncompressed records of one chunk. The station writes 1 MiB chunks, other writers a few.
  std::uint64_t max_chunk_bytes = std::uint64_t{64} << 20;
  // The uncompressed records of all chunks of a file together: at most this many bytes...
  std::uint64_t max_file_bytes = std::uint64_t{1} << 30;
  // ... and at most this many times the file's own size. The station's JSON compresses about
  // 5 times; a bomb's zeros 30,000 times.
  std::uint64_t max_file_ratio = 100;
};

// Reads the data section linearly (checking chunk CRCs, the data-section CRC and every length),
// then the summary section and footer (their CRC, and the statistics and chunk indexes against
// what the data section holds). Chunks past `limits` are refused naming the chunk.
McapContents read_mcap(std::string_view bytes, const ReadLimits& limits = {});

// The pieces read_mcap is built from, for reading by index.

// One record of `bytes`: its content views `bytes`.
struct RecordView {
  Opcode opcode = Opcode::header;
  std::uint64_t offset = 0;
  std::string_view content;

  std::uint64_t length() const { return kRecordPrefixBytes + content.size(); }
};

// The record at `offset`; McapError when its prefix or its content runs past the end.
RecordView record_at(std::string_view bytes, std::uint64_t offset);

// The record of type Record (SchemaRecord, ChunkIndexRecord, ...): checks the opcode and that
// the fields fit in the content (later fields a newer writer may add are ignored).
template <class Record>
Record parse(const RecordView& r);

// A chunk's records, decompressed, their size and CRC checked; `chunk_offset` names the chunk in
// errors. A chunk declaring more than `max_bytes` is refused before anything is allocated.
std::string chunk_records(const ChunkRecord& chunk, std::uint64_t chunk_offset,
                          std::uint64_t max_bytes = ReadLimits{}.max_chunk_bytes);

// The footer and the summary section, read from the end of the file as an indexed reader does.
struct McapSummary {
  FooterRecord footer;
  std::vector<SchemaRecord> schemas;
  std::vector<ChannelRecord> channels;
  std::optional<StatisticsRecord> statistics;
  std::vector<ChunkIndexRecord> chunk_indexes;
  std::vector<MetadataIndexRecord> metadata_indexes;
  std::vector<SummaryOffsetRecord> summary_offsets;
};
McapSummary read_summary(std::string_view bytes);

}  // namespace avk::app::mcap
