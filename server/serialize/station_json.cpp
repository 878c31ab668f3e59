#include "server/serialize/station.hpp"

#include "server/serialize/values.hpp"
#include "server/serialize/vocabulary.hpp"

namespace avk::server {

using nlohmann::json;

json datum_json(const std::optional<vehicle::LatLon>& datum) {
  return datum ? json{{"lat_deg", datum->lat_deg}, {"lon_deg", datum->lon_deg}} : json();
}

json health_json(const HealthStatus& h) {
  return {{"status", "ok"},
          {"server_version", h.server_version},
          {"session_id", h.session_id},
          {"vehicle_id", h.vehicle_id ? json(*h.vehicle_id) : json()},
          {"vehicles", h.vehicle_ids},
          {"utc_ms", h.utc_ms},
          {"clock_s", optional_json(h.clock_s)},
          {"realtime_factor", optional_json(h.realtime_factor)},
          {"session_start_clock_s", optional_json(h.session_start_clock_s)},
          {"datum", datum_json(h.datum)},
          {"store",
           {{"engine", h.store.engine},
            {"state", h.store.spooling ? "spooling" : "connected"},
            {"spooled", h.store.spooled},
            {"spool", h.store.spool_path.empty() ? json() : json(h.store.spool_path)},
            {"last_error", h.store.last_error.empty() ? json() : json(h.store.last_error)}}}};
}

json map_tiles_json(const app::tiles::MapTileInfo* tiles,
                    const std::optional<vehicle::LatLon>& datum) {
  json j = {{"available", tiles != nullptr},
            {"source", nullptr},
            {"name", nullptr},
            {"format", nullptr},
            {"minzoom", nullptr},
            {"maxzoom", nullptr},
            {"bounds", nullptr},
            {"tile_url", nullptr}};
  if (tiles) {
    j["source"] = tiles->source;
    j["name"] = tiles->name;
    j["format"] = tiles->format;
    j["minzoom"] = tiles->min_zoom;
    j["maxzoom"] = tiles->max_zoom;
    if (tiles->bounds_deg) j["bounds"] = *tiles->bounds_deg;
    j["tile_url"] = "/api/v1/tiles/{z}/{x}/{y}";
  }
  j["datum"] = datum_json(datum);
  return j;
}

json stream_hello_json(const std::string& server_version, const std::string& session_id,
                       const std::vector<std::string>& topics) {
  json j = vocabulary_json();
  j["type"] = "hello";
  j["server_version"] = server_version;
  j["session_id"] = session_id;
  j["topics"] = topics;
  return j;
}

json stream_status_json(const std::string& kind, const std::string& level,
                        const std::string& message, std::uint64_t suppressed_before,
                        const std::string& vehicle_id) {
  json j = {{"kind", kind},
            {"level", level},
            {"message", message},
            {"suppressed_before", suppressed_before}};
  if (!vehicle_id.empty()) j["vehicle_id"] = vehicle_id;
  return j;
}

}  // namespace avk::server
