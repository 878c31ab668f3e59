#include "app/mcap_reader.hpp"

#include <zstd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <utility>

namespace avk::app::mcap {

namespace {

// zstd cannot expand more than this: an RLE block of 4 bytes yields at most 128 KiB.
constexpr std::uint64_t kZstdMaxRatio = 32768;

std::string hex(std::uint8_t op) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(op));
  return buf;
}

std::string record_name(Opcode op) {
  switch (op) {
    case Opcode::header:
      return "Header";
    case Opcode::footer:
      return "Footer";
    case Opcode::schema:
      return "Schema";
    case Opcode::channel:
      return "Channel";
    case Opcode::message:
      return "Message";
    case Opcode::chunk:
      return "Chunk";
    case Opcode::message_index:
      return "Message Index";
    case Opcode::chunk_index:
      return "Chunk Index";
    case Opcode::attachment:
      return "Attachment";
    case Opcode::attachment_index:
      return "Attachment Index";
    case Opcode::statistics:
      return "Statistics";
    case Opcode::metadata:
      return "Metadata";
    case Opcode::metadata_index:
      return "Metadata Index";
    case Opcode::summary_offset:
      return "Summary Offset";
    case Opcode::data_end:
      return "Data End";
  }
  return "record of opcode " + hex(static_cast<std::uint8_t>(op));
}

std::string where(const RecordView& r) {
  return record_name(r.opcode) + " record at offset " + std::to_string(r.offset);
}

std::string chunk_at(std::uint64_t offset) {
  return "chunk at offset " + std::to_string(offset) + ": ";
}

// a * b, or the largest u64 when that overflows.
std::uint64_t times_or_max(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  return b != 0 && a > kMax / b ? kMax : a * b;
}

// Before anything of the chunk is allocated or inflated.
void check_chunk_size(const ChunkRecord& chunk, std::uint64_t chunk_offset,
                      std::uint64_t max_bytes) {
  if (chunk.uncompressed_size > max_bytes) {
    throw McapError(chunk_at(chunk_offset) + "uncompressed_size " +
                    std::to_string(chunk.uncompressed_size) + " is more than a chunk may hold (" +
                    std::to_string(max_bytes) + " bytes)");
  }
}

// A bounds-checked little-endian cursor over a record's content (or a map or array inside it).
class Fields {
 public:
  Fields(std::string_view data, std::uint64_t data_offset, std::string context)
      : data_(data), data_offset_(data_offset), context_(std::move(context)) {}
  explicit Fields(const RecordView& r)
      : Fields(r.content, r.offset + kRecordPrefixBytes, where(r)) {}

  std::size_t remaining() const { return data_.size() - pos_; }

  std::string_view bytes(std::uint64_t n, const char* field) {
    if (n > remaining()) {
      throw McapError(context_ + ": field '" + field + "' at offset " +
                      std::to_string(data_offset_ + pos_) + " needs " + std::to_string(n) +
                      " bytes, " + std::to_string(remaining()) + " remain");
    }
    const std::string_view v = data_.substr(pos_, n);
    pos_ += n;
    return v;
  }

  template <class T>
  T le(const char* field) {
    const std::string_view b = bytes(sizeof(T), field);
    T v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      v = static_cast<T>(
          v |
          static_cast<T>(static_cast<std::uint64_t>(static_cast<std::uint8_t>(b[i])) << (8 * i)));
    }
    return v;
  }
  std::uint8_t u8(const char* field) { return le<std::uint8_t>(field); }
  std::uint16_t u16(const char* field) { return le<std::uint16_t>(field); }
  std::uint32_t u32(const char* field) { return le<std::uint32_t>(field); }
  std::uint64_t u64(const char* field) { return le<std::uint64_t>(field); }

  std::string string(const char* field) { return std::string(bytes(u32(field), field)); }
  std::string_view rest() { return bytes(remaining(), "data"); }

  // A Map or Array: a u32 byte length and entries that must fill it exactly.
  Fields u32_prefixed(const char* field) {
    const std::uint32_t n = u32(field);
    const std::uint64_t at = data_offset_ + pos_;
    return Fields(bytes(n, field), at, context_ + ", field '" + field + "'");
  }

 private:
  std::string_view data_;
  std::uint64_t data_offset_;
  std::string context_;
  std::size_t pos_ = 0;
};

// Reads the fields that mcap_records.hpp lists for each record.
struct Decoder {
  Fields& f;

  void opcode(Opcode& v, const char* name) { v = static_cast<Opcode>(f.u8(name)); }
  void u16(std::uint16_t& v, const char* name) { v = f.u16(name); }
  void u32(std::uint32_t& v, const char* name) { v = f.u32(name); }
  void u64(std::uint64_t& v, const char* name) { v = f.u64(name); }
  void string(std::string& v, const char* name) { v = f.string(name); }
  void rest(std::string& v, const char*) { v = std::string(f.rest()); }
  void u64_bytes(std::string_view& v, const char* name) { v = f.bytes(f.u64(name), name); }
  void string_map(std::map<std::string, std::string>& out, const char* name) {
    Fields m = f.u32_prefixed(name);
    while (m.remaining() > 0) {
      std::string key = m.string("key");
      out[std::move(key)] = m.string("value");
    }
  }
  void u16_u64_map(std::map<std::uint16_t, std::uint64_t>& out, const char* name) {
    Fields m = f.u32_prefixed(name);
    while (m.remaining() > 0) {
      const std::uint16_t key = m.u16("key");
      out[key] = m.u64("value");
    }
  }
  void index_entries(std::vector<MessageIndexEntry>& out, const char* name) {
    Fields m = f.u32_prefixed(name);
    while (m.remaining() > 0) {
      MessageIndexEntry e;
      e.log_time_ns = m.u64("log_time");
      e.offset = m.u64("offset");
      out.push_back(e);
    }
  }
};

bool is_known(std::uint8_t op) {
  return op >= static_cast<std::uint8_t>(Opcode::header) &&
         op <= static_cast<std::uint8_t>(Opcode::data_end);
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

RecordView record_at(std::string_view bytes, std::uint64_t offset) {
  const std::uint64_t remain = offset <= bytes.size() ? bytes.size() - offset : 0;
  if (remain < kRecordPrefixBytes) {
    throw McapError("truncated: record at offset " + std::to_string(offset) +
                    " needs 9 bytes for its opcode and length, " + std::to_string(remain) +
                    " remain");
  }
  Fields prefix(bytes.substr(offset, kRecordPrefixBytes), offset, "record");
  const auto op = prefix.u8("opcode");
  const std::uint64_t length = prefix.u64("length");
  if (length > remain - kRecordPrefixBytes) {
    throw McapError("truncated: record at offset " + std::to_string(offset) + " (opcode " +
                    hex(op) + ") claims " + std::to_string(length) + " bytes, " +
                    std::to_string(remain - kRecordPrefixBytes) + " remain");
  }
  return RecordView{static_cast<Opcode>(op), offset,
                    bytes.substr(offset + kRecordPrefixBytes, length)};
}

template <class Record>
Record parse(const RecordView& r) {
  if (r.opcode != Record::opcode) {
    throw McapError("record at offset " + std::to_string(r.offset) + ": expected a " +
                    record_name(Record::opcode) + " record (opcode " +
                    hex(static_cast<std::uint8_t>(Record::opcode)) + "), found opcode " +
                    hex(static_cast<std::uint8_t>(r.opcode)));
  }
  Fields f(r);
  Decoder d{f};
  Record out;
  fields(d, out);
  return out;
}

template HeaderRecord parse(const RecordView&);
template FooterRecord parse(const RecordView&);
template SchemaRecord parse(const RecordView&);
template ChannelRecord parse(const RecordView&);
template MessageRecord parse(const RecordView&);
template ChunkRecord parse(const RecordView&);
template MessageIndexRecord parse(const RecordView&);
template ChunkIndexRecord parse(const RecordView&);
template StatisticsRecord parse(const RecordView&);
template MetadataRecord parse(const RecordView&);
template MetadataIndexRecord parse(const RecordView&);
template SummaryOffsetRecord parse(const RecordView&);
template DataEndRecord parse(const RecordView&);

std::string chunk_records(const ChunkRecord& chunk, std::uint64_t chunk_offset,
                          std::uint64_t max_bytes) {
  const std::string at = chunk_at(chunk_offset);
  check_chunk_size(chunk, chunk_offset, max_bytes);
  std::string records;
  if (chunk.compression.empty() || (chunk.records.empty() && chunk.uncompressed_size == 0)) {
    if (chunk.records.size() != chunk.uncompressed_size) {
      throw McapError(at + "uncompressed_size " + std::to_string(chunk.uncompressed_size) +
                      " but its uncompressed records hold " + std::to_string(chunk.records.size()) +
                      " bytes");
    }
    records = std::string(chunk.records);
  } else if (chunk.compression == "zstd") {
    const std::uint64_t claimed = chunk.uncompressed_size;
    if (claimed / kZstdMaxRatio > chunk.records.size()) {
      throw McapError(at + "uncompressed_size " + std::to_string(claimed) + " from " +
                      std::to_string(chunk.records.size()) +
                      " compressed bytes is more than zstd can give");
    }
    // The first frame's declared size (a chunk may hold several frames).
    const unsigned long long framed =
        ZSTD_getFrameContentSize(chunk.records.data(), chunk.records.size());
    if (framed == ZSTD_CONTENTSIZE_ERROR) {
      throw McapError(at + "its records are not a zstd frame");
    }
    if (framed != ZSTD_CONTENTSIZE_UNKNOWN && framed > claimed) {
      throw McapError(at + "uncompressed_size " + std::to_string(claimed) +
                      " but its zstd frame holds " + std::to_string(framed) + " bytes");
    }
    records.resize(claimed);
    const std::size_t n =
        ZSTD_decompress(records.data(), records.size(), chunk.records.data(), chunk.records.size());
    if (ZSTD_isError(n)) {
      throw McapError(at + "zstd: " + ZSTD_getErrorName(n));
    }
    if (n != claimed) {
      throw McapError(at + "uncompressed_size " + std::to_string(claimed) + " but zstd gave " +
                      std::to_string(n) + " bytes");
    }
  } else {
    throw McapError(at + "unsupported compression '" + chunk.compression +
                    "' (this station reads none and zstd)");
  }
  if (chunk.uncompressed_crc != 0 && crc32(records) != chunk.uncompressed_crc) {
    throw McapError(at + "CRC mismatch");
  }
  return records;
}

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
