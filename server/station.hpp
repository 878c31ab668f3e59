#pragma once
// The ground station behind /api/v1: the route table of the REST API and its adapters, each of
// which reads the request, calls one use case of app/ and writes the answer (server/serialize).
// Missions run on the vehicle loops of the station's fleet (app::Context); each vehicle's live
// feed goes to the stream and to the Foxglove connection (docs/foxglove.md), named by its id.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/collision_watch.hpp"
#include "app/context.hpp"
#include "app/foxglove_live.hpp"
#include "app/live_feeds.hpp"
#include "app/tiles/map_tiles.hpp"
#include "app/vehicle_loop.hpp"
#include "server/http/router.hpp"
#include "server/stream_feed.hpp"
#include "server/stream_hub.hpp"
#include "vehicle/gpsd_ais.hpp"

namespace avk::server {

struct StationOptions {
  std::string db_path;
  std::string token;  // bearer token for control endpoints (and for any non-loopback client)
  std::string server_version;
  // The vehicles missions run on (simulated, or M200s over their links), each with its own
  // loop; none: a station that only reads.
  std::vector<app::VehicleLoopOptions> vehicles;
  // Where the local grid lies on the earth (`--datum`): the Foxglove connection's LocationFix for
  // a simulated vehicle, whose navigation has no latitude/longitude of its own.
  std::optional<vehicle::LatLon> datum;
  // AIS traffic watched through gpsd (`--ais HOST:PORT`), placed about `datum`; none: no traffic.
  std::optional<vehicle::GpsdAisOptions> ais;
  // The collision watch over the fleet and its AIS contacts; none: not watched.
  std::optional<app::CollisionWatchOptions> collision_watch = app::CollisionWatchOptions{};
  // The dashboard's offline map background (`--tiles`); none: GET /tiles says it is unavailable.
  std::shared_ptr<const app::tiles::MapTiles> tiles;
};

// A CKT file of a long campaign is larger than any other request body.
inline constexpr std::size_t kCktImportBodyLimitBytes = std::size_t{64} << 20;

// What POST /vehicles/{vid}/maneuvers/simulate flies when the vehicle is not the station's
// simulated one.
inline constexpr const char* kDefaultManeuverSimKind = "catamaran:m200";

class Station final : public Router {
 public:
  Station(StationOptions options, StreamHub& hub);
  ~Station() override;

  // Marks missions whose process died as interrupted and starts the vehicle loop.
  void start();
  // Interrupts a running mission (stored, resumable), flushes and stops the vehicle.
  void shutdown();

  app::Context& context() { return context_; }

 private:
  // Each vehicle's feeds: the stream's and the Foxglove connection's, told the same things.
  struct VehicleFeeds {
    VehicleFeeds(StreamHub& hub, const std::string& vehicle_id, app::foxglove::TurnPredictor p,
                 std::optional<vehicle::LatLon> datum);
    StreamFeed stream;
    app::foxglove::FoxgloveLive foxglove;
    app::LiveFeeds both;
  };
  std::vector<app::FleetVehicle> make_fleet();
  void add_routes();

  StationOptions options_;
  StreamHub& hub_;
  std::vector<std::unique_ptr<VehicleFeeds>> feeds_;
  app::Context context_;
};

}  // namespace avk::server
