#include "server/routes/routes.hpp"

#include "app/vehicles.hpp"
#include "server/api_params.hpp"
#include "server/serialize/vehicles.hpp"

namespace avk::server {

void add_vehicle_routes(RouteTable& routes, app::Context& ctx) {
  routes.get(
      "/api/v1/vehicles",
      [&ctx](const ApiRequest& r, const PathParams&) {
        const Format f = negotiate(r, true);
        const auto vehicles = app::list_vehicles(ctx);
        if (f == Format::csv) return csv_response(vehicles_csv(vehicles));
        return json_response(vehicles_json(vehicles));
      },
      kJsonOrCsv);
  routes.get("/api/v1/vehicles/{vid}", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::get_vehicle(ctx, p.at("vid")), false,
                  [](const app::VehicleStatus& v) { return json_response(vehicle_json(v)); });
  });
}

}  // namespace avk::server
