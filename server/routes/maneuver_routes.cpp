#include "server/routes/routes.hpp"

#include "app/encounters.hpp"
#include "app/maneuvers.hpp"
#include "server/api_params.hpp"
#include "server/maneuver_requests.hpp"
#include "server/serialize/maneuvers.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"

namespace avk::server {

void add_maneuver_routes(RouteTable& routes, app::Context& ctx) {
  routes.post_question("/api/v1/vehicles/{vid}/maneuvers/evaluate", [&ctx](const ApiRequest& r,
                                                                           const PathParams& p) {
    const auto request = maneuver_request(body_object(r, "the encounter"), p.at("vid"));
    if (!request) return problem_of(request.error(), true);
    return answer(app::evaluate_maneuvers(ctx, request->query), true,
                  [&](const app::ManeuverEvaluation& e) {
                    return ApiResponse{200, "application/json",
                                       maneuver_evaluation_text(e, request->path_step_s)};
                  });
  });
  routes.get(
      "/api/v1/vehicles/{vid}/maneuvers/ongoing", [&ctx](const ApiRequest& r, const PathParams& p) {
        return answer(
            app::evaluate_ongoing(ctx, ongoing_query(r, p.at("vid"))), false,
            [](const app::OngoingManeuver& o) { return json_response(ongoing_maneuver_json(o)); });
      });
  routes.post_question("/api/v1/vehicles/{vid}/maneuvers/simulate", [&ctx](const ApiRequest& r,
                                                                           const PathParams& p) {
    auto request = simulate_request(body_object(r, "the maneuver"));
    if (!request) return problem_of(request.error(), true);
    const std::string vid = p.at("vid");
    // A simulated vehicle of the station flies its own setup; anything else (a
    // real boat, another vehicle's id) the calibrated M200's defaults.
    const app::VehicleLoop* loop = ctx.vehicle_loop(vid);
    const bool own_setup = loop && vehicle::is_simulated(app::kind_of(loop->options()));
    request->query.setup =
        own_setup ? loop->options().setup : sim::default_sim_setup(kDefaultManeuverSimKind);
    return answer(
        app::simulate_maneuver(request->query), true, [&](const app::SimulatedManeuver& m) {
          return json_response(
              maneuver_simulation_json(m, *request, vid, own_setup, kDefaultManeuverSimKind));
        });
  });
}

}  // namespace avk::server
