#include <gtest/gtest.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/mcap/reader.hpp"
#include "app/mcap/writer.hpp"
#include "support/mcap_bytes.hpp"

namespace {

using namespace avk::app::mcap;
using namespace avk::testing::mcap_bytes;

std::uint64_t u64_at(const std::string& bytes, std::uint64_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i)
    v = (v << 8) | static_cast<std::uint8_t>(bytes[at + i]);
  return v;
}
std::uint32_t u32_at(const std::string& bytes, std::uint64_t at) {
  return static_cast<std::uint32_t>(u64_at(bytes + std::string(4, '\0'), at));
}

std::string error_of(std::string_view bytes) {
  try {
    read_mcap(bytes);
  } catch (const McapError& e) {
    return e.what();
  }
  return "no error";
}

std::string json_message(int i) {
  std::string s = R"({"timestamp":{"sec":)" + std::to_string(i) +
                  R"(,"nsec":0},"frame_id":"grid","pose":{"position":{"x":)" +
                  std::to_string(i * 0.5) + R"(,"y":1.5,"z":0}}})";
  return s;
}

struct Sample {
  std::string bytes;
  std::uint16_t pose = 0, nav = 0, quiet = 0, raw = 0;
  std::map<std::uint16_t, std::vector<std::string>> sent;  // per channel, in order
  std::uint64_t first_ns = 0, last_ns = 0;
};

// Four channels (one without messages, one without schema), interleaved messages over several
// chunks, metadata before, between and after the chunks.
Sample write_sample(Compression compression, int messages, std::size_t chunk_size = 4096,
                    Writer::Sink sink = {}) {
  Writer w(WriterOptions{compression, chunk_size, "x-avk", "avk-test"}, std::move(sink));
  Sample s;
  const std::uint16_t pose_schema = w.add_schema("foxglove.PoseInFrame", "jsonschema", "{}");
  const std::uint16_t nav_schema = w.add_schema("avk.Navigation", "jsonschema", R"({"a":1})");
  s.pose = w.add_channel(pose_schema, "/vehicle/pose", "json", {{"frame", "grid"}, {"k", "v"}});
  s.nav = w.add_channel(nav_schema, "/vehicle/navigation", "json");
  s.quiet = w.add_channel(nav_schema, "/never", "json");
  s.raw = w.add_channel(0, "/raw", "x-bytes");
  w.add_metadata("mission", {{"id", "7"}, {"name", "Figure 4-1"}});
  s.first_ns = 1'700'000'000'000'000'000;
  for (int i = 0; i < messages; ++i) {
    const std::uint64_t t = s.first_ns + static_cast<std::uint64_t>(i / 2) * 200'000'000;
    const std::uint16_t ch = i % 7 == 3 ? s.raw : (i % 2 == 0 ? s.pose : s.nav);
    const std::string data = ch == s.raw ? std::string("\0\x01\x02", 3) : json_message(i);
    w.add_message(ch, t, t - 1000, data);
    s.sent[ch].push_back(data);
    s.last_ns = t;
    if (i == messages / 2) w.add_metadata("halfway", {});
  }
  w.add_metadata("end", {{"reason", "done"}});
  s.bytes = w.finish();
  return s;
}

class McapRoundTrip : public ::testing::TestWithParam<Compression> {};

TEST_P(McapRoundTrip, ReadsBackWhatWasWritten) {
  const Sample s = write_sample(GetParam(), 3000);
  const McapContents c = read_mcap(s.bytes);
  EXPECT_EQ(c.profile, "x-avk");
  EXPECT_EQ(c.library, "avk-test");
  ASSERT_EQ(c.schemas.size(), 2u);
  EXPECT_EQ(c.schemas[0], (SchemaRecord{1, "foxglove.PoseInFrame", "jsonschema", "{}"}));
  EXPECT_EQ(c.schemas[1], (SchemaRecord{2, "avk.Navigation", "jsonschema", R"({"a":1})"}));
  ASSERT_EQ(c.channels.size(), 4u);
  const std::map<std::string, std::string> pose_meta{{"frame", "grid"}, {"k", "v"}};
  const auto by_id = [&](std::uint16_t id) {
    for (const ChannelRecord& ch : c.channels) {
      if (ch.id == id) return ch;
    }
    return ChannelRecord{};
  };
  EXPECT_EQ(by_id(s.pose), (ChannelRecord{s.pose, 1, "/vehicle/pose", "json", pose_meta}));
  EXPECT_EQ(by_id(s.nav), (ChannelRecord{s.nav, 2, "/vehicle/navigation", "json", {}}));
  EXPECT_EQ(by_id(s.quiet), (ChannelRecord{s.quiet, 2, "/never", "json", {}}));
  EXPECT_EQ(by_id(s.raw), (ChannelRecord{s.raw, 0, "/raw", "x-bytes", {}}));

  ASSERT_EQ(c.messages.size(), 3000u);
  std::map<std::uint16_t, std::size_t> seen;
  std::uint64_t previous = 0;
  for (const MessageRecord& m : c.messages) {
    const std::size_t k = seen[m.channel_id]++;
    ASSERT_LT(k, s.sent.at(m.channel_id).size());
    EXPECT_EQ(m.data, s.sent.at(m.channel_id)[k]);
    EXPECT_EQ(m.sequence, k + 1) << "sequence numbers count per channel from 1";
    EXPECT_EQ(m.publish_time_ns, m.log_time_ns - 1000);
    EXPECT_GE(m.log_time_ns, previous);
    previous = m.log_time_ns;
  }
  EXPECT_EQ(c.messages.front().log_time_ns, s.first_ns);
  EXPECT_EQ(c.messages.back().log_time_ns, s.last_ns);

  ASSERT_EQ(c.metadata.size(), 3u);
  std::map<std::string, std::map<std::string, std::string>> metadata;
  for (const MetadataRecord& m : c.metadata)
    metadata[m.name] = m.entries;
  EXPECT_EQ(metadata["mission"],
            (std::map<std::string, std::string>{{"id", "7"}, {"name", "Figure 4-1"}}));
  EXPECT_TRUE(metadata.contains("halfway"));
  EXPECT_EQ(metadata["end"].at("reason"), "done");
  EXPECT_GT(c.chunk_count, 10u) << "3000 messages of ~100 bytes in 4 KiB chunks";
}

TEST_P(McapRoundTrip, StatisticsCountWhatTheFileHolds) {
  const Sample s = write_sample(GetParam(), 1001);
  const McapContents c = read_mcap(s.bytes);
  ASSERT_TRUE(c.statistics);
  const StatisticsRecord& st = *c.statistics;
  EXPECT_EQ(st.message_count, 1001u);
  EXPECT_EQ(st.schema_count, 2u);
  EXPECT_EQ(st.channel_count, 4u);
  EXPECT_EQ(st.attachment_count, 0u);
  EXPECT_EQ(st.metadata_count, 3u);
  EXPECT_EQ(st.chunk_count, c.chunk_count);
  EXPECT_EQ(st.message_start_time_ns, s.first_ns);
  EXPECT_EQ(st.message_end_time_ns, s.last_ns);
  std::map<std::uint16_t, std::uint64_t> counts;
  for (const auto& [ch, sent] : s.sent)
    counts[ch] = sent.size();
  EXPECT_EQ(st.channel_message_counts, counts);
  EXPECT_FALSE(st.channel_message_counts.contains(s.quiet));
}

// Footer -> summary offsets -> chunk indexes -> the chunks and their message indexes, as an
// indexed reader seeks.
TEST_P(McapRoundTrip, IndexesPointAtTheirRecords) {
  const Sample s = write_sample(GetParam(), 2000);
  const McapSummary summary = read_summary(s.bytes);
  ASSERT_EQ(summary.summary_offsets.size(), 5u);
  const std::vector<Opcode> groups{Opcode::schema, Opcode::channel, Opcode::statistics,
                                   Opcode::chunk_index, Opcode::metadata_index};
  EXPECT_EQ(summary.summary_offsets.front().group_start, summary.footer.summary_start);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const SummaryOffsetRecord& o = summary.summary_offsets[g];
    EXPECT_EQ(o.group_opcode, groups[g]);
    std::uint64_t at = o.group_start;
    while (at < o.group_start + o.group_length) {
      const RecordView r = record_at(s.bytes, at);
      EXPECT_EQ(r.opcode, groups[g]) << "group " << g << " at " << at;
      at += r.length();
    }
    EXPECT_EQ(at, o.group_start + o.group_length);
  }
  EXPECT_EQ(record_at(s.bytes, summary.footer.summary_offset_start).opcode, Opcode::summary_offset);

  ASSERT_GT(summary.chunk_indexes.size(), 5u);
  std::size_t indexed_messages = 0;
  std::uint64_t previous_end = 0;
  for (const ChunkIndexRecord& ci : summary.chunk_indexes) {
    // The raw bytes at chunk_start_offset: opcode 0x06 and a content length of chunk_length - 9.
    ASSERT_LT(ci.chunk_start_offset + 9, s.bytes.size());
    EXPECT_EQ(static_cast<std::uint8_t>(s.bytes[ci.chunk_start_offset]), 0x06);
    EXPECT_EQ(u64_at(s.bytes, ci.chunk_start_offset + 1), ci.chunk_length - 9);
    const ChunkRecord chunk = parse<ChunkRecord>(record_at(s.bytes, ci.chunk_start_offset));
    EXPECT_EQ(chunk.compression, to_string(GetParam()));
    EXPECT_EQ(ci.compression, chunk.compression);
    EXPECT_EQ(ci.compressed_size, chunk.records.size());
    EXPECT_EQ(ci.uncompressed_size, chunk.uncompressed_size);
    EXPECT_EQ(ci.message_start_time_ns, chunk.message_start_time_ns);
    EXPECT_EQ(ci.message_end_time_ns, chunk.message_end_time_ns);
    EXPECT_LE(chunk.message_start_time_ns, chunk.message_end_time_ns);
    EXPECT_GE(chunk.message_start_time_ns, previous_end);
    previous_end = chunk.message_end_time_ns;
    EXPECT_NE(chunk.uncompressed_crc, 0u);
    const std::string records = chunk_records(chunk, ci.chunk_start_offset);
    EXPECT_EQ(records.size(), chunk.uncompressed_size);

    // The message indexes follow the chunk directly and fill message_index_length.
    std::uint64_t mi_total = 0;
    std::uint64_t expected_at = ci.chunk_start_offset + ci.chunk_length;
    for (const auto& [channel_id, mi_offset] : ci.message_index_offsets) {
      EXPECT_EQ(mi_offset, expected_at);
      const RecordView r = record_at(s.bytes, mi_offset);
      const MessageIndexRecord mi = parse<MessageIndexRecord>(r);
      EXPECT_EQ(mi.channel_id, channel_id);
      mi_total += r.length();
      expected_at += r.length();
      for (const MessageIndexEntry& e : mi.records) {
        const MessageRecord m = parse<MessageRecord>(record_at(records, e.offset));
        EXPECT_EQ(m.channel_id, channel_id);
        EXPECT_EQ(m.log_time_ns, e.log_time_ns);
        EXPECT_GE(e.log_time_ns, ci.message_start_time_ns);
        EXPECT_LE(e.log_time_ns, ci.message_end_time_ns);
        ++indexed_messages;
      }
    }
    EXPECT_EQ(mi_total, ci.message_index_length);
  }
  EXPECT_EQ(indexed_messages, 2000u);

  ASSERT_EQ(summary.metadata_indexes.size(), 3u);
  for (const MetadataIndexRecord& mi : summary.metadata_indexes) {
    const RecordView r = record_at(s.bytes, mi.offset);
    EXPECT_EQ(r.length(), mi.length);
    EXPECT_EQ(parse<MetadataRecord>(r).name, mi.name);
  }
}

TEST_P(McapRoundTrip, CrcsAreComputed) {
  const Sample s = write_sample(GetParam(), 200);
  const McapSummary summary = read_summary(s.bytes);
  EXPECT_NE(summary.footer.summary_crc, 0u);
  const RecordView data_end = record_at(s.bytes, summary.footer.summary_start - 13);
  ASSERT_EQ(data_end.opcode, Opcode::data_end);
  const std::uint32_t crc = parse<DataEndRecord>(data_end).data_section_crc;
  EXPECT_EQ(crc, crc32(std::string_view(s.bytes).substr(0, data_end.offset)));
}

// A long mission's file goes to its destination as each chunk closes, never held whole: the
// pieces make the same file as the one written in memory.
TEST_P(McapRoundTrip, ASinkGetsTheSameFileAPieceAtATime) {
  const Sample in_memory = write_sample(GetParam(), 3000);
  std::string streamed;
  std::size_t pieces = 0;
  std::size_t largest = 0;
  const Sample sunk = write_sample(GetParam(), 3000, 4096, [&](std::string_view piece) {
    streamed.append(piece);
    ++pieces;
    largest = std::max(largest, piece.size());
  });
  EXPECT_TRUE(sunk.bytes.empty());
  EXPECT_EQ(streamed, in_memory.bytes);
  EXPECT_GT(pieces, 10u);
  EXPECT_LT(largest, in_memory.bytes.size() / 4);
  EXPECT_EQ(read_mcap(streamed).messages.size(), 3000u);
}

TEST_P(McapRoundTrip, EmptyFileIsValid) {
  Writer w(WriterOptions{GetParam(), 1024, "", "avk-station"});
  const McapContents c = read_mcap(w.finish());
  EXPECT_TRUE(c.messages.empty());
  EXPECT_EQ(c.chunk_count, 0u);
  ASSERT_TRUE(c.statistics);
  EXPECT_EQ(c.statistics->message_start_time_ns, 0u);
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapRoundTrip,
                         ::testing::Values(Compression::none, Compression::zstd),
                         [](const auto& info) {
                           return std::string(info.param == Compression::none ? "none" : "zstd");
                         });

TEST(McapWriter, CompressionNamesAreThoseOfTheFile) {
  EXPECT_STREQ(to_string(Compression::none), "");
  EXPECT_STREQ(to_string(Compression::zstd), "zstd");
}

TEST(McapWriter, Crc32IsZlibs) {
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);  // the CRC-32 check value
}

// magic, then <0x01><u64 content length><u32 profile length><profile><u32 length><library>.
TEST(McapWriter, HeaderBytesMatchTheSpecificationLayout) {
  Writer w(WriterOptions{Compression::none, 1024, "x-avk", "lib"});
  const std::string b = w.finish();
  ASSERT_GT(b.size(), 41u);
  EXPECT_EQ(b.substr(0, 8), std::string("\x89MCAP0\r\n", 8));
  EXPECT_EQ(b.substr(8, 1 + 8 + 4 + 5 + 4 + 3), std::string("\x01\x10\0\0\0\0\0\0\0", 9) +
                                                    std::string("\x05\0\0\0", 4) + "x-avk" +
                                                    std::string("\x03\0\0\0", 4) + "lib");
  // No channels: the Data End follows, its CRC over magic and header.
  EXPECT_EQ(b.substr(33, 9), std::string("\x0F\x04\0\0\0\0\0\0\0", 9));
  EXPECT_EQ(u32_at(b, 42), crc32(std::string_view(b).substr(0, 33)));
  // The file ends with a Footer of 20 content bytes and the magic.
  EXPECT_EQ(b.substr(b.size() - 8), std::string(kMagic));
  EXPECT_EQ(b.substr(b.size() - 37, 9), std::string("\x02\x14\0\0\0\0\0\0\0", 9));
}

TEST(McapWriter, SequenceCountsPerChannel) {
  Writer w(WriterOptions{Compression::none, 1 << 20, "", "t"});
  const std::uint16_t a = w.add_channel(0, "/a", "json");
  const std::uint16_t b = w.add_channel(0, "/b", "json");
  EXPECT_EQ(a, 1u);
  EXPECT_EQ(b, 2u);
  for (std::uint64_t t : {1, 2, 3})
    w.add_message(a, t, t, "{}");
  w.add_message(b, 4, 4, "{}");
  w.add_message(a, 5, 5, "{}");
  const McapContents c = read_mcap(w.finish());
  std::vector<std::uint32_t> sequences;
  for (const MessageRecord& m : c.messages)
    sequences.push_back(m.sequence);
  EXPECT_EQ(sequences, (std::vector<std::uint32_t>{1, 2, 3, 1, 4}));
}

TEST(McapWriter, LogTimeGoingBackThrowsNamingBothTimes) {
  Writer w;
  const std::uint16_t ch = w.add_channel(0, "/a", "json");
  w.add_message(ch, 2000, 2000, "{}");
  w.add_message(ch, 2000, 1500, "{}");  // equal log times are in order
  try {
    w.add_message(ch, 1999, 1999, "{}");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1999"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2000"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_mcap(w.finish()).messages.size(), 2u);
}

TEST(McapWriter, UnknownIdsAndUseAfterFinishThrow) {
  Writer w;
  EXPECT_THROW(w.add_channel(1, "/a", "json"), std::invalid_argument);
  EXPECT_THROW(w.add_message(1, 0, 0, ""), std::invalid_argument);
  w.finish();
  EXPECT_THROW(w.add_schema("s", "jsonschema", "{}"), std::logic_error);
  EXPECT_THROW(w.finish(), std::logic_error);
}

TEST(McapReader, BadMagic) {
  EXPECT_EQ(error_of(""), "not an MCAP file: bad magic at offset 0");
  EXPECT_EQ(error_of("PK\x03\x04 this is a zip file"), "not an MCAP file: bad magic at offset 0");
  std::string b = write_sample(Compression::zstd, 10).bytes;
  b.back() = 'x';
  EXPECT_EQ(error_of(b), "not an MCAP file: bad magic at offset " + std::to_string(b.size() - 8));
}

TEST(McapReader, EveryTruncationIsAnError) {
  for (Compression c : {Compression::none, Compression::zstd}) {
    const std::string b = write_sample(c, 40, 512).bytes;
    for (std::size_t n = 0; n < b.size(); ++n) {
      EXPECT_THROW(read_mcap(std::string_view(b).substr(0, n)), McapError) << n;
    }
  }
}

TEST(McapReader, TruncationNamesTheRecordAndItsClaim) {
  const std::string b = write_sample(Compression::none, 40, 512).bytes;
  const std::uint64_t chunk = read_summary(b).chunk_indexes.at(0).chunk_start_offset;
  const std::uint64_t claimed = u64_at(b, chunk + 1);
  EXPECT_EQ(error_of(std::string_view(b).substr(0, chunk + 9 + 40)),
            "truncated: record at offset " + std::to_string(chunk) + " (opcode 0x06) claims " +
                std::to_string(claimed) + " bytes, 40 remain");
}

// Every byte is covered by a CRC, a length or the magic: no flip may pass, none may crash.
TEST(McapReader, EveryFlippedByteIsAnError) {
  for (Compression c : {Compression::none, Compression::zstd}) {
    const std::string b = write_sample(c, 30, 512).bytes;
    for (std::size_t i = 0; i < b.size(); ++i) {
      std::string corrupt = b;
      corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5A);
      EXPECT_THROW(read_mcap(corrupt), McapError) << to_string(c) << " byte " << i;
    }
  }
}

// With every CRC zeroed, corrupt bytes reach the parsers behind the CRCs: each flip must be
// read or refused with McapError, never crash or throw anything else.
TEST(McapReader, CorruptionBehindZeroedCrcsIsReadOrRefused) {
  for (Compression c : {Compression::none, Compression::zstd}) {
    std::string b = write_sample(c, 30, 512).bytes;
    const McapSummary summary = read_summary(b);
    for (const ChunkIndexRecord& ci : summary.chunk_indexes) {
      b.replace(ci.chunk_start_offset + 9 + 24, 4, le<std::uint32_t>(0));  // uncompressed_crc
    }
    b.replace(summary.footer.summary_start - 4, 4, le<std::uint32_t>(0));  // data_section_crc
    b.replace(b.size() - 12, 4, le<std::uint32_t>(0));                     // summary_crc
    ASSERT_EQ(read_mcap(b).messages.size(), 30u);
    std::size_t refused = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      std::string corrupt = b;
      corrupt[i] = static_cast<char>(corrupt[i] ^ 0xA5);
      try {
        read_mcap(corrupt);
      } catch (const McapError&) {
        ++refused;
      }
    }
    EXPECT_GT(refused, b.size() / 4) << to_string(c);
  }
}

TEST(McapReader, FlippedChunkByteIsACrcMismatch) {
  std::string b = write_sample(Compression::none, 30, 512).bytes;
  const ChunkIndexRecord ci = read_summary(b).chunk_indexes.at(1);
  // Message data near the end of the chunk: the record structure stays intact.
  b[ci.chunk_start_offset + ci.chunk_length - 3] ^= 0x01;
  EXPECT_EQ(error_of(b),
            "chunk at offset " + std::to_string(ci.chunk_start_offset) + ": CRC mismatch");
}

TEST(McapReader, UnsupportedCompressionIsNamed) {
  const std::string chunk =
      record(Opcode::chunk, le<std::uint64_t>(0) + le<std::uint64_t>(0) + le<std::uint64_t>(100) +
                                le<std::uint32_t>(0) + str("lz4") + le<std::uint64_t>(3) + "abc");
  EXPECT_EQ(error_of(hand_built_file(chunk)),
            "chunk at offset 29: unsupported compression 'lz4' (this station reads none and zstd)");
}

TEST(McapReader, AbsurdUncompressedSizeIsRefusedBeforeAllocating) {
  const std::string chunk =
      record(Opcode::chunk, le<std::uint64_t>(0) + le<std::uint64_t>(0) +
                                le<std::uint64_t>(std::uint64_t{1} << 62) + le<std::uint32_t>(0) +
                                str("zstd") + le<std::uint64_t>(4) + "\x28\xB5\x2F\xFD");
  EXPECT_NE(error_of(hand_built_file(chunk)).find("chunk at offset 29: uncompressed_size"),
            std::string::npos);
}

TEST(McapReader, TheZeroFrameIsZstd) {
  const std::string frame = zero_frame(300'000);
  EXPECT_EQ(ZSTD_getFrameContentSize(frame.data(), frame.size()), 300'000u);
  std::string out(300'000, 'x');
  ASSERT_EQ(ZSTD_decompress(out.data(), out.size(), frame.data(), frame.size()), 300'000u);
  EXPECT_EQ(out, std::string(300'000, '\0'));
  EXPECT_EQ(read_mcap(hand_built_file(zero_chunk(9 * 1000))).chunk_count, 1u);
}

// The zstd bomb: 32 KiB of file declaring 1 GiB in one chunk is refused from the declared size,
// before anything is allocated or inflated.
TEST(McapReader, AChunkDeclaringMoreThanAChunkMayHoldIsRefusedBeforeInflating) {
  const std::uint64_t size = 9 * 119'304'647;  // 1 GiB - 1
  const std::string file = hand_built_file(zero_chunk(size));
  EXPECT_LT(file.size(), 33'000u);
  EXPECT_EQ(error_of(file),
            "chunk at offset 29: uncompressed_size 1073741823 is more than a "
            "chunk may hold (67108864 bytes)");
}

// Chunks that each fit are refused once together they declare more than the file may hold:
// 100 times its own size.
TEST(McapReader, ChunksDeclaringMoreThanAFileMayHoldAreRefused) {
  const std::uint64_t size = 9 * 1'000'000;  // 8.6 MiB a chunk, about 1 kB of file
  std::string chunks;
  for (int i = 0; i < 3; ++i)
    chunks += zero_chunk(size);
  const std::string file = hand_built_file(chunks);
  EXPECT_EQ(error_of(file),
            "chunk at offset 29: uncompressed_size 9000000 would bring the "
            "file's chunks to 9000000 bytes, more than a file of " +
                std::to_string(file.size()) + " bytes may hold (" +
                std::to_string(100 * file.size()) + ")");
}

// The absolute cap of a file, with limits small enough to reach cheaply: the third chunk of
// 900,000 bytes passes 2 MiB and is refused before it is inflated.
TEST(McapReader, ChunksPastTheFileCapAreRefusedAtTheChunkThatPassesIt) {
  const std::string chunk = zero_chunk(9 * 100'000);
  const std::string file = hand_built_file(chunk + chunk + chunk);
  ReadLimits limits;
  limits.max_chunk_bytes = 1 << 20;
  limits.max_file_bytes = 2 << 20;
  limits.max_file_ratio = 1'000'000;
  EXPECT_EQ(read_mcap(hand_built_file(chunk + chunk), limits).chunk_count, 2u);
  try {
    read_mcap(file, limits);
    ADD_FAILURE() << "read";
  } catch (const McapError& e) {
    EXPECT_EQ(std::string(e.what()), "chunk at offset " + std::to_string(29 + 2 * chunk.size()) +
                                         ": uncompressed_size 900000 would bring the file's "
                                         "chunks to 2700000 bytes, more than a file of " +
                                         std::to_string(file.size()) + " bytes may hold (2097152)");
  }
  limits.max_chunk_bytes = 899'999;
  EXPECT_THROW(read_mcap(hand_built_file(chunk), limits), McapError);
}

TEST(McapReader, RecordLengthsBeyondTheFileAreRefused) {
  // A chunk whose records field claims 2^63 bytes inside a small record.
  const std::string chunk = record(
      Opcode::chunk, le<std::uint64_t>(0) + le<std::uint64_t>(0) + le<std::uint64_t>(3) +
                         le<std::uint32_t>(0) + str("") + le<std::uint64_t>(1ull << 63) + "abc");
  EXPECT_NE(error_of(hand_built_file(chunk)).find("field 'records'"), std::string::npos);
  // A channel whose metadata map claims more bytes than the record holds.
  const std::string channel =
      record(Opcode::channel, le<std::uint16_t>(1) + le<std::uint16_t>(0) + str("/a") +
                                  str("json") + le<std::uint32_t>(0xFFFFFFF0u));
  EXPECT_NE(
      error_of(hand_built_file(channel)).find("Channel record at offset 29: field 'metadata'"),
      std::string::npos);
}

TEST(McapReader, MessageOnAnUnknownChannelIsAnError) {
  const std::string message =
      record(Opcode::message, le<std::uint16_t>(7) + le<std::uint32_t>(1) + le<std::uint64_t>(5) +
                                  le<std::uint64_t>(5) + "{}");
  EXPECT_EQ(error_of(hand_built_file(message)),
            "Message record at offset 29: channel id 7 has no Channel record before it");
}

// Unchunked messages, CRCs of 0, no summary and an application record: a valid file too.
TEST(McapReader, ReadsAnUnchunkedFileWithoutSummary) {
  const std::string data =
      record(Opcode::schema, le<std::uint16_t>(1) + str("s") + str("jsonschema") + str("{}")) +
      record(Opcode::channel, le<std::uint16_t>(3) + le<std::uint16_t>(1) + str("/a") +
                                  str("json") + le<std::uint32_t>(10) + str("k") + str("v")) +
      record(static_cast<Opcode>(0x80), "application") +
      record(Opcode::message, le<std::uint16_t>(3) + le<std::uint32_t>(9) + le<std::uint64_t>(5) +
                                  le<std::uint64_t>(4) + "{\"x\":1}");
  const McapContents c = read_mcap(hand_built_file(data));
  EXPECT_EQ(c.library, "hand");
  ASSERT_EQ(c.channels.size(), 1u);
  EXPECT_EQ(c.channels[0].metadata.at("k"), "v");
  ASSERT_EQ(c.messages.size(), 1u);
  EXPECT_EQ(c.messages[0].sequence, 9u);
  EXPECT_EQ(c.messages[0].publish_time_ns, 4u);
  EXPECT_EQ(c.messages[0].data, "{\"x\":1}");
  EXPECT_FALSE(c.statistics);
}

}  // namespace
