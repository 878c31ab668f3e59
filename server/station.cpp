#include "server/station.hpp"

#include <algorithm>
#include <chrono>

#include "app/foxglove_scene.hpp"
#include "app/traffic_watch.hpp"
#include "server/map_tile_routes.hpp"
#include "server/routes/routes.hpp"
#include "server/serialize/station.hpp"
#include "server/serialize/vocabulary.hpp"

namespace avk::server {

Station::VehicleFeeds::VehicleFeeds(StreamHub& hub, const std::string& vehicle_id,
                                    app::foxglove::TurnPredictor p,
                                    std::optional<vehicle::LatLon> datum)
    : stream(hub, vehicle_id),
      foxglove(hub.foxglove(), std::move(p), datum),
      both({&stream, &foxglove}) {}

std::vector<app::FleetVehicle> Station::make_fleet() {
  std::vector<app::FleetVehicle> fleet;
  for (const auto& v : options_.vehicles) {
    auto predictor = [this](const std::string& vid, double speed_mps, double dheading_deg,
                            const kinematics::Pose& start) {
      return app::foxglove::scene_predictions(context_, vid, speed_mps, dheading_deg, start);
    };
    feeds_.push_back(std::make_unique<VehicleFeeds>(hub_, app::planned_vehicle_info(v).id,
                                                    predictor, options_.datum));
    fleet.push_back({v, &feeds_.back()->both});
  }
  return fleet;
}

Station::Station(StationOptions options, StreamHub& hub)
    : Router(options.token),
      options_(std::move(options)),
      hub_(hub),
      context_(options_.db_path, make_fleet()) {
  // AIS positions are placed on the local grid, which only a datum puts on the earth.
  if (options_.ais) {
    if (!options_.datum) throw std::invalid_argument("AIS traffic needs the station's datum");
    context_.watch_traffic({*options_.ais, *options_.datum, {}});
  }
  if (options_.collision_watch && !options_.vehicles.empty())
    context_.watch_collisions(*options_.collision_watch);
  add_routes();
}

Station::~Station() {
  shutdown();
}

void Station::start() {
  context_.start();
}

void Station::shutdown() {
  context_.shutdown("the server stopped");
  for (auto& f : feeds_)
    f->foxglove.withdraw();
}

void Station::add_routes() {
  app::Context& ctx = context_;
  // How much work each answer takes (docs/api.md, "Request work"); a route not named here is
  // cheap. Immediate: answered on an I/O thread, so /health answers while every request worker
  // is busy. Expensive: work that grows with the stored data (whole missions, every turn, a
  // simulation, a fit), limited in number and per client address.
  const RouteCost expensive{Workload::expensive};
  const RouteTable::Costs costs = {
      {"GET /api/v1/health", {Workload::immediate}},
      {"GET /api/v1/meta", {Workload::immediate}},
      {"GET /api/v1/missions/{id}/current", expensive},
      {"GET /api/v1/missions/{id}/export", expensive},
      {"POST /api/v1/missions/{id}/harvest", expensive},
      {"GET /api/v1/vehicles/{vid}/ckt/yaw-rate", expensive},
      {"POST /api/v1/vehicles/{vid}/ckt/import", expensive},
      // A table built for the answer: the vehicle's other turns, or its table over yaw rate.
      {"GET /api/v1/vehicles/{vid}/predict",
       {Workload::cheap, {"without_turn", "without_mission", "initial_yaw_rate"}}},
      {"POST /api/v1/vehicles/{vid}/maneuvers/evaluate", expensive},
      {"POST /api/v1/vehicles/{vid}/maneuvers/simulate", expensive},
      {"GET /api/v1/vehicles/{vid}/compare", expensive},
      {"POST /api/v1/vehicles/{vid}/models", expensive},
      {"GET /api/v1/vehicles/{vid}/models/sweep", expensive},
      {"GET /api/v1/models/{id}/headings", expensive},
  };
  RouteTable routes(*this, costs);

  // --- the station -------------------------------------------------------------------------
  routes.get("/api/v1/health", [this, &ctx](const ApiRequest&, const PathParams&) {
    const std::vector<app::VehicleLoop*> loops = ctx.vehicle_loops();
    app::VehicleLoop* loop = loops.empty() ? nullptr : loops.front();
    HealthStatus h;
    h.server_version = options_.server_version;
    h.session_id = hub_.session_id();
    if (loop) h.vehicle_id = loop->info().id;
    for (const app::VehicleLoop* l : loops)
      h.vehicle_ids.push_back(l->info().id);
    h.utc_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                   std::chrono::system_clock::now().time_since_epoch())
                   .count();
    if (loop) {
      // Before the loop's first telemetry tick its snapshot has no time yet: the clock is at its
      // start then. The fleet shares one station clock; the first vehicle's shows it.
      const app::VehicleLoopOptions& v = loop->options();
      h.clock_s = std::max(loop->snapshot().t_s, v.start_clock_s);
      h.realtime_factor = v.realtime_factor;
      h.session_start_clock_s = v.start_clock_s;
    }
    h.datum = options_.datum;
    h.store = app::store_link_view(ctx.db_path());
    return json_response(health_json(h));
  });
  // The names the station uses (event kinds with their severity, helm modes, link states, turn
  // statuses), so a client keeps no copy of its own.
  routes.get("/api/v1/meta",
             [](const ApiRequest&, const PathParams&) { return json_response(vocabulary_json()); });

  add_vehicle_routes(routes, ctx);
  add_mission_routes(routes, ctx, options_.datum);
  add_turn_routes(routes, ctx);
  add_ckt_routes(routes, ctx);
  add_current_routes(routes, ctx);
  add_prediction_routes(routes, ctx);
  add_maneuver_routes(routes, ctx);
  add_model_routes(routes, ctx);
  add_traffic_routes(routes, ctx);

  // --- the map background (avk serve --tiles) ---------------------------------------------
  add_map_tile_routes(*this, options_.tiles, options_.datum);

  routes.check_costs();
}

}  // namespace avk::server
