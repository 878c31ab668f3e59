#include "app/traffic.hpp"
#include "server/routes/routes.hpp"
#include "server/serialize/traffic.hpp"

namespace avk::server {

void add_traffic_routes(RouteTable& routes, app::Context& ctx) {
  // The AIS contacts the station watches, on the local grid: what an operator sees on the Live
  // map and what the maneuver evaluation can take as contacts.
  routes.get("/api/v1/traffic", [&ctx](const ApiRequest&, const PathParams&) {
    return json_response(traffic_json(app::traffic(ctx)));
  });
}

}  // namespace avk::server
