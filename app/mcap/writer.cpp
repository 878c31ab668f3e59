#include "app/mcap/writer.hpp"

#include <zstd.h>

#include <boost/crc.hpp>
#include <limits>
#include <stdexcept>

namespace avk::app::mcap {

std::uint32_t crc32(std::string_view bytes) {
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

namespace {

void put_u8(std::string& out, std::uint8_t v) {
  out.push_back(static_cast<char>(v));
}

template <class T>
void put_le(std::string& out, T v) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>(static_cast<std::uint8_t>(v >> (8 * i))));
  }
}
void put_u16(std::string& out, std::uint16_t v) {
  put_le(out, v);
}
void put_u32(std::string& out, std::uint32_t v) {
  put_le(out, v);
}
void put_u64(std::string& out, std::uint64_t v) {
  put_le(out, v);
}

std::uint32_t u32_length(std::size_t n, const char* what) {
  if (n > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument(std::string("MCAP: ") + what + " longer than 4 GiB");
  }
  return static_cast<std::uint32_t>(n);
}

void put_string(std::string& out, std::string_view s) {
  put_u32(out, u32_length(s.size(), "string"));
  out.append(s);
}

// Maps and arrays carry their byte length in front: reserve it, fill the entries, patch it.
template <class Fill>
void put_u32_prefixed(std::string& out, Fill fill) {
  const std::size_t at = out.size();
  put_u32(out, 0);
  fill();
  const std::uint32_t n = u32_length(out.size() - at - 4, "map or array");
  for (std::size_t i = 0; i < 4; ++i)
    out[at + i] = static_cast<char>(n >> (8 * i));
}

// Writes the fields that app/mcap/records.hpp lists for each record.
struct Encoder {
  std::string& out;

  void opcode(Opcode v, const char*) { put_u8(out, static_cast<std::uint8_t>(v)); }
  void u16(std::uint16_t v, const char*) { put_u16(out, v); }
  void u32(std::uint32_t v, const char*) { put_u32(out, v); }
  void u64(std::uint64_t v, const char*) { put_u64(out, v); }
  void string(std::string_view v, const char*) { put_string(out, v); }
  void rest(std::string_view v, const char*) { out.append(v); }
  void u64_bytes(std::string_view v, const char*) {
    put_u64(out, v.size());
    out.append(v);
  }
  void string_map(const std::map<std::string, std::string>& m, const char*) {
    put_u32_prefixed(out, [&] {
      for (const auto& [k, v] : m) {
        put_string(out, k);
        put_string(out, v);
      }
    });
  }
  void u16_u64_map(const std::map<std::uint16_t, std::uint64_t>& m, const char*) {
    put_u32_prefixed(out, [&] {
      for (const auto& [k, v] : m) {
        put_u16(out, k);
        put_u64(out, v);
      }
    });
  }
  void index_entries(const std::vector<MessageIndexEntry>& entries, const char*) {
    put_u32_prefixed(out, [&] {
      for (const MessageIndexEntry& e : entries) {
        put_u64(out, e.log_time_ns);
        put_u64(out, e.offset);
      }
    });
  }
};

// Appends <opcode><u64 content length><content>; returns the record's offset in `out`.
template <class Record>
std::uint64_t put(std::string& out, const Record& r) {
  const std::size_t at = out.size();
  put_u8(out, static_cast<std::uint8_t>(Record::opcode));
  put_u64(out, 0);
  Encoder e{out};
  fields(e, r);
  const std::uint64_t n = out.size() - at - kRecordPrefixBytes;
  for (std::size_t i = 0; i < 8; ++i)
    out[at + 1 + i] = static_cast<char>(n >> (8 * i));
  return at;
}

std::string zstd_compress(std::string_view in) {
  std::string out(ZSTD_compressBound(in.size()), '\0');
  const std::size_t n =
      ZSTD_compress(out.data(), out.size(), in.data(), in.size(), ZSTD_CLEVEL_DEFAULT);
  if (ZSTD_isError(n)) {
    throw std::runtime_error(std::string("MCAP: zstd compression failed: ") + ZSTD_getErrorName(n));
  }
  out.resize(n);
  return out;
}

template <class Record>
void check_id_space(const std::vector<Record>& v, const char* what) {
  if (v.size() >= std::numeric_limits<std::uint16_t>::max()) {
    throw std::invalid_argument(std::string("MCAP: more than 65535 ") + what);
  }
}

}  // namespace

const char* to_string(Compression c) {
  switch (c) {
    case Compression::none:
      return "";
    case Compression::zstd:
      return "zstd";
  }
  return "";
}

Writer::Writer(WriterOptions options, Sink sink)
    : options_(std::move(options)), sink_(std::move(sink)) {
  out_.append(kMagic);
  put(out_, HeaderRecord{options_.profile, options_.library});
}

void Writer::flush() {
  if (!sink_ || out_.empty()) return;
  data_crc_.process_bytes(out_.data(), out_.size());
  sink_(out_);
  flushed_ += out_.size();
  out_.clear();
}

void Writer::check_open() const {
  if (finished_) throw std::logic_error("MCAP writer: already finished");
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding,
                                 std::string_view data) {
  check_open();
  check_id_space(schemas_, "schemas");
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back(SchemaRecord{id, name, encoding, std::string(data)});
  schema_written_.push_back(false);
  return id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic,
                                  const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  check_open();
  if (schema_id > schemas_.size()) {
    throw std::invalid_argument("MCAP channel '" + topic + "': unknown schema id " +
                                std::to_string(schema_id));
  }
  check_id_space(channels_, "channels");
  const auto id = static_cast<std::uint16_t>(channels_.size() + 1);
  channels_.push_back(ChannelRecord{id, schema_id, topic, message_encoding, metadata});
  channel_written_.push_back(false);
  sequences_.push_back(0);
  return id;
}

// Readers need a channel's Schema and Channel records before its first message; writing them
// into the chunk that first uses them keeps channels without messages out of the chunks.
void Writer::write_definitions_into_chunk(std::uint16_t channel_id) {
  if (channel_written_[channel_id - 1]) return;
  const ChannelRecord& channel = channels_[channel_id - 1];
  if (channel.schema_id != 0 && !schema_written_[channel.schema_id - 1]) {
    put(chunk_records_, schemas_[channel.schema_id - 1]);
    schema_written_[channel.schema_id - 1] = true;
  }
  put(chunk_records_, channel);
  channel_written_[channel_id - 1] = true;
}

void Writer::add_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                         std::uint64_t publish_time_ns, std::string_view data) {
  check_open();
  if (channel_id == 0 || channel_id > channels_.size()) {
    throw std::invalid_argument("MCAP message: unknown channel id " + std::to_string(channel_id));
  }
  if (first_log_time_ns_ && log_time_ns < last_log_time_ns_) {
    throw std::invalid_argument("MCAP message on '" + channels_[channel_id - 1].topic +
                                "': log time " + std::to_string(log_time_ns) +
                                " ns is earlier than the previous message's " +
                                std::to_string(last_log_time_ns_) + " ns");
  }
  write_definitions_into_chunk(channel_id);
  if (chunk_message_index_.empty()) chunk_start_time_ns_ = log_time_ns;
  chunk_end_time_ns_ = log_time_ns;
  const std::uint32_t sequence = ++sequences_[channel_id - 1];
  const std::uint64_t offset =
      put(chunk_records_,
          MessageRecord{channel_id, sequence, log_time_ns, publish_time_ns, std::string(data)});
  chunk_message_index_[channel_id].push_back(MessageIndexEntry{log_time_ns, offset});

  if (!first_log_time_ns_) first_log_time_ns_ = log_time_ns;
  last_log_time_ns_ = log_time_ns;
  ++message_count_;
  ++channel_message_counts_[channel_id];
  if (chunk_records_.size() >= options_.chunk_size_bytes) close_chunk();
}

void Writer::close_chunk() {
  if (chunk_records_.empty()) return;
  const std::string compressed =
      options_.compression == Compression::zstd ? zstd_compress(chunk_records_) : std::string();
  const std::string_view records =
      options_.compression == Compression::zstd ? std::string_view(compressed) : chunk_records_;
  ChunkIndexRecord index;
  index.message_start_time_ns = chunk_message_index_.empty() ? 0 : chunk_start_time_ns_;
  index.message_end_time_ns = chunk_message_index_.empty() ? 0 : chunk_end_time_ns_;
  index.chunk_start_offset =
      flushed_ + put(out_, ChunkRecord{index.message_start_time_ns, index.message_end_time_ns,
                                       chunk_records_.size(), crc32(chunk_records_),
                                       to_string(options_.compression), records});
  index.chunk_length = offset() - index.chunk_start_offset;
  const std::uint64_t message_index_start = offset();
  for (auto& [channel_id, entries] : chunk_message_index_) {
    index.message_index_offsets[channel_id] =
        flushed_ + put(out_, MessageIndexRecord{channel_id, std::move(entries)});
  }
  index.message_index_length = offset() - message_index_start;
  index.compression = to_string(options_.compression);
  index.compressed_size = records.size();
  index.uncompressed_size = chunk_records_.size();
  chunk_indexes_.push_back(std::move(index));
  chunk_records_.clear();
  chunk_message_index_.clear();
  flush();
}

// Metadata may not sit inside a chunk; the open chunk is appended to the file only when it
// closes, so the record lands in the data section before it.
void Writer::add_metadata(const std::string& name,
                          const std::map<std::string, std::string>& entries) {
  check_open();
  const std::uint64_t at = flushed_ + put(out_, MetadataRecord{name, entries});
  metadata_indexes_.push_back(MetadataIndexRecord{at, offset() - at, name});
}

std::string Writer::finish() {
  check_open();
  close_chunk();
  // Summary Schema and Channel records duplicate data-section ones; those of channels without
  // messages go to the data section here.
  for (std::size_t i = 0; i < schemas_.size(); ++i) {
    if (!schema_written_[i]) put(out_, schemas_[i]);
  }
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    if (!channel_written_[i]) put(out_, channels_[i]);
  }
  boost::crc_32_type data_crc = data_crc_;
  data_crc.process_bytes(out_.data(), out_.size());
  put(out_, DataEndRecord{data_crc.checksum()});
  flush();

  const std::size_t summary_at = out_.size();  // in out_
  const std::uint64_t summary_start = offset();
  std::vector<SummaryOffsetRecord> groups;
  auto group = [&](Opcode op, auto&& records) {
    if (records.empty()) return;
    const std::uint64_t start = offset();
    for (const auto& r : records)
      put(out_, r);
    groups.push_back(SummaryOffsetRecord{op, start, offset() - start});
  };
  group(Opcode::schema, schemas_);
  group(Opcode::channel, channels_);
  StatisticsRecord statistics;
  statistics.message_count = message_count_;
  statistics.schema_count = static_cast<std::uint16_t>(schemas_.size());
  statistics.channel_count = static_cast<std::uint32_t>(channels_.size());
  statistics.metadata_count = static_cast<std::uint32_t>(metadata_indexes_.size());
  statistics.chunk_count = static_cast<std::uint32_t>(chunk_indexes_.size());
  statistics.message_start_time_ns = first_log_time_ns_.value_or(0);
  statistics.message_end_time_ns = first_log_time_ns_ ? last_log_time_ns_ : 0;
  statistics.channel_message_counts = channel_message_counts_;
  group(Opcode::statistics, std::vector<StatisticsRecord>{statistics});
  group(Opcode::chunk_index, chunk_indexes_);
  group(Opcode::metadata_index, metadata_indexes_);

  const std::uint64_t summary_offset_start = offset();
  for (const SummaryOffsetRecord& g : groups)
    put(out_, g);

  // The summary CRC covers the footer's own fields before it: opcode, length and both offsets.
  std::string footer;
  put(footer, FooterRecord{summary_start, summary_offset_start, 0});
  boost::crc_32_type crc;
  crc.process_bytes(out_.data() + summary_at, out_.size() - summary_at);
  crc.process_bytes(footer.data(), footer.size() - 4);
  footer.resize(footer.size() - 4);
  put_u32(footer, crc.checksum());
  out_.append(footer);
  out_.append(kMagic);
  finished_ = true;
  if (sink_) {
    sink_(out_);
    out_.clear();
  }
  return std::move(out_);
}

}  // namespace avk::app::mcap
