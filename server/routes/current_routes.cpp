#include "server/routes/routes.hpp"

#include "app/current.hpp"
#include "app/vehicle_motion.hpp"
#include "server/serialize/currents.hpp"

namespace avk::server {

void add_current_routes(RouteTable& routes, app::Context& ctx) {
  // The station's estimate of the current the vehicle is in (the running mission's, updated at
  // every turn; else its newest mission's).
  routes.get("/api/v1/vehicles/{vid}/current", [&ctx](const ApiRequest&, const PathParams& p) {
    const std::string vid = p.at("vid");
    auto c = app::vehicle_current(ctx, vid);
    // No estimate yet is an answer, not a missing resource: a page asks on every load.
    if (!c && c.error().code == app::ErrorCode::not_found)
      return json_response({{"vehicle_id", vid}, {"estimated", false}});
    return answer(std::move(c), false, [&vid](const app::CurrentView& cur) {
      return json_response(current_json(vid, cur));
    });
  });
  // What the station has learned of how the vehicle moves on a held heading: which speed its loop
  // holds, how fast a straight-line prediction's error grows, the current it was last seen in.
  routes.get("/api/v1/vehicles/{vid}/motion", [&ctx](const ApiRequest&, const PathParams& p) {
    return answer(app::vehicle_motion(ctx, p.at("vid")), false, [](const app::VehicleMotion& m) {
      return json_response(vehicle_motion_json(m));
    });
  });
}

}  // namespace avk::server
