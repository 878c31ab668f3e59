// Writes the seed corpus of mcap_fuzz into DIR: a small mission as the station exports it (two
// navigation samples and an event), re-written by the station's writer in three layouts: zstd
// chunks, uncompressed chunks, and several small zstd chunks. The schema texts are cut to "{}":
// the Foxglove schemas alone take 50 kB, and the smoke run reads 4 KiB of a seed.
//
//   make_mcap_seeds DIR
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "app/context.hpp"
#include "app/mcap/reader.hpp"
#include "app/mcap/writer.hpp"
#include "app/mission_mcap.hpp"
#include "app/store_access.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

std::string rewritten(const app::mcap::McapContents& c, app::mcap::Compression compression,
                      std::size_t chunk_bytes) {
  app::mcap::Writer w({compression, chunk_bytes, c.profile, c.library});
  // The export numbers schemas and channels from 1 in the order the summary lists them.
  for (const auto& s : c.schemas)
    w.add_schema(s.name, s.encoding, "{}");
  for (const auto& ch : c.channels)
    w.add_channel(ch.schema_id, ch.topic, ch.message_encoding, ch.metadata);
  for (const auto& m : c.messages)
    w.add_message(m.channel_id, m.log_time_ns, m.publish_time_ns, m.data);
  for (const auto& m : c.metadata)
    w.add_metadata(m.name, m.entries);
  return w.finish();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_mcap_seeds DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  testing::TempDb db("avk_mcap_seeds");
  app::Context ctx(db.path());
  store::Store& st = app::store_of(ctx);
  st.vehicles().upsert({"seed", "usim", 2.0, 1.2});
  const std::int64_t mission = st.missions().create("seed", "seed", "{}");
  st.missions().set_status(mission, store::MissionStatus::running, "", 10.0);
  const store::NavRow nav[] = {{10.0, 0.0, 0.0, 90.0, 1.5, 90.0, 1.5, "SURVEY"},
                               {10.5, 0.75, 0.0, 91.0, 1.5, 95.0, 1.5, "SURVEY"}};
  st.navigation().append(mission, nav);
  st.missions().append_event(mission, 10.25, "note", "a seed");
  st.missions().set_status(mission, store::MissionStatus::done, "", 11.0);
  const auto exported = app::export_mission_mcap(ctx, mission);
  if (!exported) {
    std::cerr << exported.error().message << "\n";
    return 1;
  }
  auto contents = app::mcap::read_mcap(exported->bytes);
  std::ranges::sort(contents.schemas, {}, &app::mcap::SchemaRecord::id);
  std::ranges::sort(contents.channels, {}, &app::mcap::ChannelRecord::id);
  using app::mcap::Compression;
  const std::pair<const char*, std::string> seeds[] = {
      {"station_zstd.mcap", rewritten(contents, Compression::zstd, 1 << 20)},
      {"station_none.mcap", rewritten(contents, Compression::none, 1 << 20)},
      {"station_small_chunks.mcap", rewritten(contents, Compression::zstd, 400)},
  };
  std::filesystem::create_directories(dir);
  for (const auto& [name, bytes] : seeds) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    std::cout << name << ": " << bytes.size() << " bytes\n";
  }
  return 0;
}
