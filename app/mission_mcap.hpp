#pragma once
// A mission as an MCAP recording (docs/foxglove.md, "MCAP recordings"): the channels and schemas
// of the live Foxglove connection (app/foxglove/channels.hpp) with every stored navigation
// sample, turn and event, plus the stored turns themselves and metadata records holding the
// rest of the mission, so that a file written by one station imports into another unchanged.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/mcap/writer.hpp"
#include "app/result.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::app {

class Context;

// The version of the station's MCAP layout (channels and metadata records) in the avk.mission
// metadata record; an import takes only the versions it knows.
inline constexpr const char* kMissionMcapVersion = "1";
// IANA's registration of MCAP (application/vnd.mcap), for downloads.
inline constexpr const char* kMcapMediaType = "application/vnd.mcap";

struct McapExportOptions {
  mcap::Compression compression = mcap::Compression::zstd;
  // Positions on the earth for the location channel (foxglove.LocationFix): the grid's datum.
  // None: the location channel is left out (the store keeps grid positions only).
  std::optional<vehicle::LatLon> datum;
};

// Messages per channel, in the file's channel order.
struct McapChannelCounts {
  std::vector<std::pair<std::string, std::uint64_t>> per_topic;
  std::uint64_t total() const;
  std::uint64_t of(const std::string& topic) const;
};

struct McapExport {
  std::int64_t mission_id = 0;
  std::string vehicle_id;
  std::string bytes;  // the file; empty when it went to a sink
  McapChannelCounts messages;
};

// not_found for an unknown mission; invalid_argument naming "datum" for a datum off the earth
// (both before anything goes to the sink). With a sink the file goes to it a chunk at a time as
// it is written, instead of into `bytes`: an export of a long mission is never held whole.
Result<McapExport> export_mission_mcap(Context& ctx, std::int64_t mission_id,
                                       const McapExportOptions& options = {},
                                       const mcap::Writer::Sink& sink = {});

struct McapImport {
  std::int64_t mission_id = 0;         // the new mission
  std::int64_t source_mission_id = 0;  // its id in the station that wrote the file
  std::string vehicle_id;
  std::size_t nav_samples = 0;
  std::size_t events = 0;
  std::size_t turns = 0;
  std::size_t condition_sets = 0;
  bool current = false;
  McapChannelCounts messages;  // as read
};

// A file written by export_mission_mcap, as a new mission. Everything is read and checked before
// anything is stored, and stored in one transaction: a file that fails leaves the database as
// it was. invalid_argument (field "file") naming what is wrong: not MCAP, not the station's (no
// avk.mission metadata), another layout version, a message that does not parse or holds a value
// outside the navigation ranges (vehicle/nav_ranges.hpp) or navigation going back in time (its
// topic and sequence), counts that disagree with the mission record.
Result<McapImport> import_mission_mcap(Context& ctx, std::string_view bytes);

}  // namespace avk::app
