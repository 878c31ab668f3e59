// The pieces read_mcap is built from (app/mcap/reader.hpp): one record at an offset, its fields
// by type, a chunk's records inflated and checked.
#include <zstd.h>

#include <cstdio>
#include <map>
#include <utility>

#include "app/mcap/reader.hpp"
#include "app/mcap/record_checks.hpp"

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

// Reads the fields that app/mcap/records.hpp lists for each record.
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

}  // namespace

std::string where(const RecordView& r) {
  return record_name(r.opcode) + " record at offset " + std::to_string(r.offset);
}

std::string chunk_at(std::uint64_t offset) {
  return "chunk at offset " + std::to_string(offset) + ": ";
}

void check_chunk_size(const ChunkRecord& chunk, std::uint64_t chunk_offset,
                      std::uint64_t max_bytes) {
  if (chunk.uncompressed_size > max_bytes) {
    throw McapError(chunk_at(chunk_offset) + "uncompressed_size " +
                    std::to_string(chunk.uncompressed_size) + " is more than a chunk may hold (" +
                    std::to_string(max_bytes) + " bytes)");
  }
}

bool is_known(std::uint8_t op) {
  return op >= static_cast<std::uint8_t>(Opcode::header) &&
         op <= static_cast<std::uint8_t>(Opcode::data_end);
}

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

}  // namespace avk::app::mcap
