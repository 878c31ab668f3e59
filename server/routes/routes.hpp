#pragma once
// The REST API's adapters by resource, each of which adds its routes to the station's table:
// every adapter reads the request, calls one use case of app/ and writes the answer
// (server/serialize). Station::add_routes calls them in the order of docs/api.md.

#include <optional>

#include "app/context.hpp"
#include "app/vehicle_loop.hpp"
#include "server/routes/route_table.hpp"
#include "vehicle/local_grid.hpp"

namespace avk::server {

// GET /vehicles and /vehicles/{vid}.
void add_vehicle_routes(RouteTable& routes, app::Context& ctx);
// Missions: listing, start, report, commands, the current they flew in, event log, track,
// harvest, and the MCAP export (with its location fixes placed by `datum`).
void add_mission_routes(RouteTable& routes, app::Context& ctx,
                        std::optional<vehicle::LatLon> datum);
// The recorded turns: a page of them, and one with its trajectories.
void add_turn_routes(RouteTable& routes, app::Context& ctx);
// A vehicle's CKT: the table, a cell, the table over yaw rate, export and import.
void add_ckt_routes(RouteTable& routes, app::Context& ctx);
// The current a vehicle is in and how it moves on a held heading.
void add_current_routes(RouteTable& routes, app::Context& ctx);
// A predicted turn.
void add_prediction_routes(RouteTable& routes, app::Context& ctx);
// Maneuvers: candidates scored by CPA, a maneuver in progress, one flown in the simulator (on
// the station's simulated vehicle when it is the one asked, else the default setup).
void add_maneuver_routes(RouteTable& routes, app::Context& ctx);
// The comparison of the prediction methods, and the identified yaw models.
void add_model_routes(RouteTable& routes, app::Context& ctx);
// The AIS traffic the station watches.
void add_traffic_routes(RouteTable& routes, app::Context& ctx);

}  // namespace avk::server
