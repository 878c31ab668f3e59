#pragma once
// The station's own documents: its health, the map background it serves, and the live stream's
// hello and status messages.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/store_link.hpp"
#include "app/tiles/map_tiles.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::server {

// {lat_deg, lon_deg}; null without a datum.
nlohmann::json datum_json(const std::optional<vehicle::LatLon>& datum);

// What GET /api/v1/health reports, read by the station at one moment.
struct HealthStatus {
  std::string server_version;
  std::string session_id;
  std::optional<std::string> vehicle_id;  // the station's first vehicle, when it runs any
  std::vector<std::string> vehicle_ids;   // every vehicle of its fleet, in order
  std::int64_t utc_ms = 0;                // the wall clock
  // The station clock beside the wall clock at that moment: every time of this session (nav,
  // events, turns) is in the station clock, which runs x realtime_factor on the simulator; a
  // front end shows wall-clock time as utc_ms - (clock_s - t_s) / realtime_factor * 1000.
  std::optional<double> clock_s;
  std::optional<double> realtime_factor;
  // Where this session's clock began: a mission started before it ran in an earlier session,
  // whose times the mapping above does not fit.
  std::optional<double> session_start_clock_s;
  std::optional<vehicle::LatLon> datum;
  // The database: its engine, and whether writes wait in the local spool (a PostgreSQL server
  // that is away).
  app::StoreLinkView store;
};
nlohmann::json health_json(const HealthStatus& h);

// GET /api/v1/tiles: the map tiles served (their fields null when there are none) and the datum.
nlohmann::json map_tiles_json(const app::tiles::MapTileInfo* tiles,
                              const std::optional<vehicle::LatLon>& datum);

// The hello a new stream connection receives: the vocabulary with the session and its topics.
nlohmann::json stream_hello_json(const std::string& server_version, const std::string& session_id,
                                 const std::vector<std::string>& topics);
// A `status` message; suppressed_before counts those of its kind held back since the last one;
// vehicle_id (left out when empty) is the vehicle the event is about.
nlohmann::json stream_status_json(const std::string& kind, const std::string& level,
                                  const std::string& message, std::uint64_t suppressed_before,
                                  const std::string& vehicle_id = {});

}  // namespace avk::server
