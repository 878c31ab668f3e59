#include "app/collision_watch.hpp"
#include "app/traffic.hpp"
#include "server/routes/routes.hpp"
#include "server/serialize/collision_watch.hpp"
#include "server/serialize/traffic.hpp"

namespace avk::server {

void add_traffic_routes(RouteTable& routes, app::Context& ctx) {
  // The AIS contacts the station watches, on the local grid: what an operator sees on the Live
  // map and what the maneuver evaluation can take as contacts.
  routes.get("/api/v1/traffic", [&ctx](const ApiRequest&, const PathParams&) {
    return json_response(traffic_json(app::traffic(ctx)));
  });
  // Every pair of the station's vehicles (and vehicle and AIS contact) with its predicted closest
  // approach over the watch's horizon and whether its alarm is up.
  routes.get("/api/v1/collision-watch", [&ctx](const ApiRequest&, const PathParams&) {
    return json_response(collision_watch_json(app::collision_watch_view(ctx)));
  });
}

}  // namespace avk::server
