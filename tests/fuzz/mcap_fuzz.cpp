// libFuzzer target for the MCAP reader (app/mcap/reader.cpp), built by tests/CMakeLists.txt.
// Only McapError may be thrown. What reads never holds more than the caps let it inflate, and the
// station's writer writes it back to a file that reads to the same schemas, channels, messages
// (in log-time order) and metadata. read_summary, the indexed reader's entry, only throws
// McapError too.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "app/mcap/reader.hpp"
#include "app/mcap/writer.hpp"

namespace {

using namespace avk::app::mcap;

// Small caps, so that a short input cannot make a run slow.
ReadLimits fuzz_limits() {
  ReadLimits l;
  l.max_chunk_bytes = std::uint64_t{1} << 20;
  l.max_file_bytes = std::uint64_t{16} << 20;
  return l;
}

void check_round_trip(const McapContents& c) {
  Writer w(WriterOptions{Compression::none, 512, c.profile, c.library});
  std::map<std::uint16_t, std::uint16_t> schema_ids, channel_ids;  // file's -> rewritten
  for (const SchemaRecord& s : c.schemas)
    schema_ids[s.id] = w.add_schema(s.name, s.encoding, s.data);
  for (const ChannelRecord& ch : c.channels) {
    channel_ids[ch.id] = w.add_channel(ch.schema_id ? schema_ids.at(ch.schema_id) : 0, ch.topic,
                                       ch.message_encoding, ch.metadata);
  }
  std::vector<const MessageRecord*> in_time;
  for (const MessageRecord& m : c.messages)
    in_time.push_back(&m);
  std::stable_sort(in_time.begin(), in_time.end(),
                   [](const auto* a, const auto* b) { return a->log_time_ns < b->log_time_ns; });
  for (const MessageRecord* m : in_time)
    w.add_message(channel_ids.at(m->channel_id), m->log_time_ns, m->publish_time_ns, m->data);
  for (const MetadataRecord& m : c.metadata)
    w.add_metadata(m.name, m.entries);
  const McapContents back = read_mcap(w.finish());

  if (back.schemas.size() != c.schemas.size() || back.channels.size() != c.channels.size() ||
      back.messages.size() != c.messages.size() || back.metadata != c.metadata)
    std::abort();
  for (const ChannelRecord& ch : back.channels) {
    const auto it = std::find_if(c.channels.begin(), c.channels.end(), [&](const ChannelRecord& o) {
      return channel_ids[o.id] == ch.id;
    });
    if (it == c.channels.end() || it->topic != ch.topic || it->metadata != ch.metadata)
      std::abort();
  }
  for (std::size_t i = 0; i < back.messages.size(); ++i) {
    const MessageRecord& a = *in_time[i];
    const MessageRecord& b = back.messages[i];
    if (channel_ids.at(a.channel_id) != b.channel_id || a.log_time_ns != b.log_time_ns ||
        a.publish_time_ns != b.publish_time_ns || a.data != b.data)
      std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    (void)read_summary(bytes);
  } catch (const McapError&) {
  }
  const ReadLimits limits = fuzz_limits();
  McapContents c;
  try {
    c = read_mcap(bytes, limits);
  } catch (const McapError&) {
    return 0;
  }
  // Chunked messages came out of at most max_file_bytes of records, the others out of the file.
  std::uint64_t held = 0;
  for (const MessageRecord& m : c.messages)
    held += m.data.size();
  if (held > limits.max_file_bytes + size) std::abort();
  // Channel ids run 0 to 65535; the writer numbers from 1.
  if (c.channels.size() <= 65535) check_round_trip(c);
  return 0;
}
