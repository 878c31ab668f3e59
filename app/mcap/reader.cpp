#include "app/mcap/reader.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "app/mcap/record_checks.hpp"

namespace avk::app::mcap {

namespace {

// a * b, or the largest u64 when that overflows.
std::uint64_t times_or_max(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  return b != 0 && a > kMax / b ? kMax : a * b;
}

// The records of a data section, a chunk or a summary section; the definitions seen so far.
class ContentsReader {
 public:
  // `file_bytes`: the size of the file, which bounds what its chunks may inflate to.
  ContentsReader(McapContents& out, const ReadLimits& limits, std::uint64_t file_bytes)
      : out_(out),
        limits_(limits),
        file_bytes_(file_bytes),
        max_inflated_(
            std::min(limits.max_file_bytes, times_or_max(file_bytes, limits.max_file_ratio))) {}

  // Schema and Channel records, in a chunk, the data or the summary section; false for others.
  bool definition(const RecordView& r) {
    if (r.opcode == Opcode::schema) {
      schema(r);
    } else if (r.opcode == Opcode::channel) {
      channel(r);
    } else {
      return false;
    }
    return true;
  }

  void schema(const RecordView& r) {
    SchemaRecord s = parse<SchemaRecord>(r);
    if (s.id == 0) return;  // invalid by the specification: readers ignore it
    const auto [it, added] = schema_index_.try_emplace(s.id, out_.schemas.size());
    if (added) {
      out_.schemas.push_back(std::move(s));
    } else if (out_.schemas[it->second] != s) {
      throw McapError(where(r) + ": schema id " + std::to_string(s.id) +
                      " differs from an earlier Schema record of the same id");
    }
  }

  void channel(const RecordView& r) {
    ChannelRecord c = parse<ChannelRecord>(r);
    if (c.schema_id != 0 && !schema_index_.contains(c.schema_id)) {
      throw McapError(where(r) + ": channel " + std::to_string(c.id) + " ('" + c.topic +
                      "') refers to schema id " + std::to_string(c.schema_id) +
                      ", which has no Schema record before it");
    }
    const auto [it, added] = channel_index_.try_emplace(c.id, out_.channels.size());
    if (added) {
      out_.channels.push_back(std::move(c));
    } else if (out_.channels[it->second] != c) {
      throw McapError(where(r) + ": channel id " + std::to_string(c.id) +
                      " differs from an earlier Channel record of the same id");
    }
  }

  void message(const RecordView& r) {
    MessageRecord m = parse<MessageRecord>(r);
    if (!channel_index_.contains(m.channel_id)) {
      throw McapError(where(r) + ": channel id " + std::to_string(m.channel_id) +
                      " has no Channel record before it");
    }
    ++message_counts_[m.channel_id];
    out_.messages.push_back(std::move(m));
  }

  void chunk(const RecordView& r) {
    const ChunkRecord c = parse<ChunkRecord>(r);
    check_chunk_size(c, r.offset, limits_.max_chunk_bytes);
    if (c.uncompressed_size > max_inflated_ - inflated_) {
      throw McapError(chunk_at(r.offset) + "uncompressed_size " +
                      std::to_string(c.uncompressed_size) + " would bring the file's chunks to " +
                      std::to_string(inflated_ + c.uncompressed_size) +
                      " bytes, more than a file of " + std::to_string(file_bytes_) +
                      " bytes may hold (" + std::to_string(max_inflated_) + ")");
    }
    inflated_ += c.uncompressed_size;
    const std::string records = chunk_records(c, r.offset, limits_.max_chunk_bytes);
    try {
      for (std::uint64_t at = 0; at < records.size();) {
        const RecordView inner = record_at(records, at);
        if (inner.opcode == Opcode::message) {
          message(inner);
        } else if (!definition(inner) && is_known(static_cast<std::uint8_t>(inner.opcode))) {
          throw McapError(where(inner) + " is not allowed inside a chunk");
        }
        at += inner.length();
      }
    } catch (const McapError& e) {
      throw McapError("chunk at offset " + std::to_string(r.offset) +
                      ", in its uncompressed records: " + e.what());
    }
    chunks_[r.offset] = r.length();
    ++out_.chunk_count;
  }

  const std::map<std::uint16_t, std::uint64_t>& message_counts() const { return message_counts_; }
  const std::map<std::uint64_t, std::uint64_t>& chunks() const { return chunks_; }

 private:
  McapContents& out_;
  ReadLimits limits_;
  std::uint64_t file_bytes_;
  std::uint64_t max_inflated_;                          // the records of all chunks, uncompressed
  std::uint64_t inflated_ = 0;                          // so far
  std::map<std::uint16_t, std::size_t> schema_index_;   // id -> index in out_.schemas
  std::map<std::uint16_t, std::size_t> channel_index_;  // id -> index in out_.channels
  std::map<std::uint16_t, std::uint64_t> message_counts_;
  std::map<std::uint64_t, std::uint64_t> chunks_;  // offset -> record length
};

void check_magic(std::string_view bytes, std::uint64_t offset) {
  if (bytes.size() < offset + kMagic.size() || bytes.substr(offset, kMagic.size()) != kMagic) {
    throw McapError("not an MCAP file: bad magic at offset " + std::to_string(offset));
  }
}

// The record at `offset` of a file that must go on up to its Footer.
RecordView next_record(std::string_view bytes, std::uint64_t offset) {
  if (offset == bytes.size()) {
    throw McapError("truncated: the file ends at offset " + std::to_string(offset) +
                    " without a Footer record");
  }
  return record_at(bytes, offset);
}

// Data section records; returns the offset of the record that ends it (Data End, or the first
// summary record or Footer of a file written without Data End).
std::uint64_t read_data_section(std::string_view bytes, std::uint64_t offset,
                                ContentsReader& reader, McapContents& out) {
  for (;;) {
    const RecordView r = next_record(bytes, offset);
    if (reader.definition(r)) {
      offset += r.length();
      continue;
    }
    switch (r.opcode) {
      case Opcode::message:
        reader.message(r);
        break;
      case Opcode::chunk:
        reader.chunk(r);
        break;
      case Opcode::metadata:
        out.metadata.push_back(parse<MetadataRecord>(r));
        break;
      case Opcode::message_index:
        (void)parse<MessageIndexRecord>(r);
        break;
      case Opcode::attachment:
        break;
      case Opcode::header:
        throw McapError(where(r) + ": a second Header");
      case Opcode::data_end:
      case Opcode::footer:
      case Opcode::chunk_index:
      case Opcode::attachment_index:
      case Opcode::statistics:
      case Opcode::metadata_index:
      case Opcode::summary_offset:
        return offset;
      default:
        break;  // an application's record (0x80-0xFF) or a newer format's: skipped
    }
    offset += r.length();
  }
}

void check_against_data(const McapContents& out, const ContentsReader& reader,
                        const std::vector<ChunkIndexRecord>& chunk_indexes) {
  if (out.statistics) {
    const StatisticsRecord& s = *out.statistics;
    if (s.message_count != out.messages.size() || s.chunk_count != out.chunk_count) {
      throw McapError("Statistics record: " + std::to_string(s.message_count) + " messages in " +
                      std::to_string(s.chunk_count) + " chunks, the data section holds " +
                      std::to_string(out.messages.size()) + " in " +
                      std::to_string(out.chunk_count));
    }
    if (!s.channel_message_counts.empty() && s.channel_message_counts != reader.message_counts()) {
      for (const auto& [id, n] : s.channel_message_counts) {
        const auto it = reader.message_counts().find(id);
        const std::uint64_t found = it == reader.message_counts().end() ? 0 : it->second;
        if (found != n) {
          throw McapError("Statistics record: channel " + std::to_string(id) + " has " +
                          std::to_string(n) + " messages, the data section holds " +
                          std::to_string(found));
        }
      }
      throw McapError("Statistics record: channel_message_counts misses a channel with messages");
    }
  }
  if (!chunk_indexes.empty() && chunk_indexes.size() != reader.chunks().size()) {
    throw McapError("summary: " + std::to_string(chunk_indexes.size()) +
                    " Chunk Index records for " + std::to_string(reader.chunks().size()) +
                    " chunks");
  }
  for (const ChunkIndexRecord& c : chunk_indexes) {
    const auto it = reader.chunks().find(c.chunk_start_offset);
    if (it == reader.chunks().end() || it->second != c.chunk_length) {
      throw McapError("Chunk Index record: no chunk of " + std::to_string(c.chunk_length) +
                      " bytes at offset " + std::to_string(c.chunk_start_offset));
    }
  }
}

}  // namespace

McapContents read_mcap(std::string_view bytes, const ReadLimits& limits) {
  check_magic(bytes, 0);
  McapContents out;
  const RecordView header_record = record_at(bytes, kMagic.size());
  const HeaderRecord header = parse<HeaderRecord>(header_record);
  out.profile = header.profile;
  out.library = header.library;

  ContentsReader reader(out, limits, bytes.size());
  std::uint64_t offset =
      read_data_section(bytes, kMagic.size() + header_record.length(), reader, out);
  if (const RecordView end = record_at(bytes, offset); end.opcode == Opcode::data_end) {
    const DataEndRecord data_end = parse<DataEndRecord>(end);
    if (data_end.data_section_crc != 0 &&
        crc32(bytes.substr(0, offset)) != data_end.data_section_crc) {
      throw McapError(where(end) + ": data section CRC mismatch");
    }
    offset += end.length();
  }

  // The summary section: repeated definitions must agree with the data section's.
  const std::uint64_t summary_start = offset;
  std::uint64_t summary_offset_start = 0;
  std::vector<ChunkIndexRecord> chunk_indexes;
  RecordView r;
  for (;; offset += r.length()) {
    r = next_record(bytes, offset);
    if (r.opcode == Opcode::footer) break;
    if (r.opcode != Opcode::summary_offset && summary_offset_start != 0) {
      throw McapError(where(r) + " follows the Summary Offset records");
    }
    if (reader.definition(r)) continue;
    switch (r.opcode) {
      case Opcode::statistics:
        if (out.statistics) throw McapError(where(r) + ": a second Statistics record");
        out.statistics = parse<StatisticsRecord>(r);
        break;
      case Opcode::chunk_index:
        chunk_indexes.push_back(parse<ChunkIndexRecord>(r));
        break;
      case Opcode::metadata_index:
        (void)parse<MetadataIndexRecord>(r);
        break;
      case Opcode::summary_offset:
        (void)parse<SummaryOffsetRecord>(r);
        if (summary_offset_start == 0) summary_offset_start = offset;
        break;
      case Opcode::attachment_index:
        break;
      default:
        if (is_known(static_cast<std::uint8_t>(r.opcode))) {
          throw McapError(where(r) + " is not allowed in the summary section");
        }
    }
  }

  const FooterRecord footer = parse<FooterRecord>(r);
  const std::uint64_t footer_end = offset + r.length();
  if (bytes.size() - footer_end != kMagic.size()) {
    throw McapError(where(r) + ": " + std::to_string(bytes.size() - footer_end) +
                    " bytes follow it, expected the 8 bytes of the closing magic");
  }
  check_magic(bytes, footer_end);
  const bool has_summary = summary_start != offset;
  if (footer.summary_start != (has_summary ? summary_start : 0) ||
      footer.summary_offset_start != summary_offset_start) {
    throw McapError(where(r) + ": summary_start " + std::to_string(footer.summary_start) +
                    " and summary_offset_start " + std::to_string(footer.summary_offset_start) +
                    ", the file has them at " + std::to_string(has_summary ? summary_start : 0) +
                    " and " + std::to_string(summary_offset_start));
  }
  if (footer.summary_crc != 0 && has_summary) {
    const std::uint64_t crc_end = offset + kRecordPrefixBytes + 8 + 8;
    if (crc32(bytes.substr(summary_start, crc_end - summary_start)) != footer.summary_crc) {
      throw McapError(where(r) + ": summary CRC mismatch");
    }
  }
  check_against_data(out, reader, chunk_indexes);
  return out;
}

McapSummary read_summary(std::string_view bytes) {
  check_magic(bytes, 0);
  const std::uint64_t footer_length = kRecordPrefixBytes + 8 + 8 + 4;
  if (bytes.size() < kMagic.size() + footer_length + kMagic.size()) {
    throw McapError("truncated: " + std::to_string(bytes.size()) +
                    " bytes cannot hold magic, Footer and magic");
  }
  check_magic(bytes, bytes.size() - kMagic.size());
  const std::uint64_t footer_offset = bytes.size() - kMagic.size() - footer_length;
  McapSummary s;
  s.footer = parse<FooterRecord>(record_at(bytes, footer_offset));
  if (s.footer.summary_start == 0) return s;
  if (s.footer.summary_start > footer_offset) {
    throw McapError("Footer record: summary_start " + std::to_string(s.footer.summary_start) +
                    " lies after the footer at " + std::to_string(footer_offset));
  }
  const std::string_view summary = bytes.substr(0, footer_offset);
  for (std::uint64_t at = s.footer.summary_start; at < footer_offset;) {
    const RecordView r = record_at(summary, at);
    switch (r.opcode) {
      case Opcode::schema:
        s.schemas.push_back(parse<SchemaRecord>(r));
        break;
      case Opcode::channel:
        s.channels.push_back(parse<ChannelRecord>(r));
        break;
      case Opcode::statistics:
        s.statistics = parse<StatisticsRecord>(r);
        break;
      case Opcode::chunk_index:
        s.chunk_indexes.push_back(parse<ChunkIndexRecord>(r));
        break;
      case Opcode::metadata_index:
        s.metadata_indexes.push_back(parse<MetadataIndexRecord>(r));
        break;
      case Opcode::summary_offset:
        s.summary_offsets.push_back(parse<SummaryOffsetRecord>(r));
        break;
      default:
        break;
    }
    at += r.length();
  }
  return s;
}

}  // namespace avk::app::mcap
