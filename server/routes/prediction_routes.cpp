#include "server/routes/routes.hpp"

#include <limits>

#include "app/predict.hpp"
#include "server/api_params.hpp"
#include "server/serialize/predictions.hpp"

namespace avk::server {

namespace {

app::PredictQuery predict_query(const ApiRequest& r, const std::string& vid) {
  app::PredictQuery q;
  q.vehicle_id = vid;
  // Any finite numbers here: the use case checks speed and heading change together, against
  // the vehicle's table too, so that an answer names every one that is off and its range.
  constexpr double kAny = std::numeric_limits<double>::infinity();
  const auto turn = required_numbers(r, {{"speed", -kAny, kAny}, {"dheading", -kAny, kAny}});
  q.speed_mps = turn[0];
  q.dheading_deg = turn[1];
  q.method = method_param(r).value_or(q.method);
  q.model_id = id_param(r, "model");
  const auto x = number_param(r, "x", -1e7, 1e7);
  const auto y = number_param(r, "y", -1e7, 1e7);
  const auto heading = number_param(r, "heading", -360.0, 720.0);
  if ((x || y || heading) && !(x && y && heading))
    throw bad_parameter(x ? (y ? "heading" : "y") : "x", "a pose needs x, y and heading");
  if (x) q.pose = kinematics::Pose{*x, *y, *heading};
  q.corridor_share = number_param(r, "corridor", 0.5, 0.999).value_or(q.corridor_share);
  const CurrentParam current = current_param(r);
  q.current = current.current;
  q.live_current = current.live;
  q.no_current = current.none;
  q.speed_over_ground = speed_reference_param(r);
  q.include_harvested = include_harvested_param(r);
  q.initial_yaw_rate_dps = number_param(r, "initial_yaw_rate", -90.0, 90.0);
  q.speed_after_mps = number_param(r, "speed_after", 0.0, 100.0);
  q.without_mission_id = id_param(r, "without_mission");
  q.without_turn_id = id_param(r, "without_turn");
  return q;
}

}  // namespace

void add_prediction_routes(RouteTable& routes, app::Context& ctx) {
  routes.get("/api/v1/vehicles/{vid}/predict", [&ctx](const ApiRequest& r, const PathParams& p) {
    return answer(app::predict(ctx, predict_query(r, p.at("vid"))), false,
                  [](const app::Prediction& pr) { return json_response(prediction_json(pr)); });
  });
}

}  // namespace avk::server
