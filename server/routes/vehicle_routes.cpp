#include "server/routes/routes.hpp"

#include "app/vehicle_commands.hpp"
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
  // Commands that keep the vehicle safe: control routes, like the mission commands.
  using mission::VehicleCommandKind;
  const std::pair<VehicleCommandKind, const char*> commands[] = {
      {VehicleCommandKind::hold, "hold"},
      {VehicleCommandKind::go_to, "go-to"},
      {VehicleCommandKind::return_to, "return"},
      {VehicleCommandKind::stop, "stop"}};
  for (const auto& [kind, path] : commands) {
    routes.post("/api/v1/vehicles/{vid}/" + std::string(path), [&ctx, kind](const ApiRequest& r,
                                                                            const PathParams& p) {
      const BodyNumbers b =
          body_numbers(r, {"x_m", "y_m", "radius_m", "speed_mps"},
                       "the " + std::string(mission::to_string(kind)) + " command");
      const app::VehicleCommandRequest request{kind, b.get("x_m"), b.get("y_m"), b.get("radius_m"),
                                               b.get("speed_mps")};
      return answer(app::command_vehicle(ctx, p.at("vid"), request), true,
                    [](const app::VehicleStatus& v) { return json_response(vehicle_json(v)); });
    });
  }
}

}  // namespace avk::server
