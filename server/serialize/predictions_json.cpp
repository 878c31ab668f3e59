#include "server/serialize/predictions.hpp"

#include "server/serialize/currents.hpp"
#include "server/serialize/values.hpp"

namespace avk::server {

using nlohmann::json;

json prediction_json(const app::Prediction& p) {
  const app::PredictQuery& q = p.query;
  json j = {{"method", app::to_string(q.method)},
            {"vehicle_id", q.vehicle_id},
            {"speed_mps", q.speed_mps},
            {"dheading_deg", q.dheading_deg},
            {"frame", q.pose ? "world" : "normalized"}};
  if (q.method == app::PredictionMethod::avk) {
    j["advance_m"] = optional_json(p.advance_m);
    j["transfer_m"] = optional_json(p.transfer_m);
    j["exact_cell"] = p.exact_cell ? json(*p.exact_cell) : json();
    j["extrapolated"] = p.extrapolated ? json(*p.extrapolated) : json();
    j["table_source"] = p.table_source ? json(*p.table_source) : json();
    j["snapshot_id"] = optional_json(p.snapshot_id);
    j["short_of_goal"] = p.short_of_goal;
    if (q.initial_yaw_rate_dps) {
      j["cell_source"] = p.cell_source ? json(*p.cell_source) : json();
      j["yaw_rate_clamped"] = p.yaw_rate_clamped ? json(*p.yaw_rate_clamped) : json();
    }
    if (p.corridor) {
      const auto& c = *p.corridor;
      j["corridor"] = {{"share", c.share},
                       {"n_turns", c.n_turns},
                       {"s_m", c.s_m},
                       {"half_width_m", c.half_width_m},
                       {"left", points_json(c.left)},
                       {"right", points_json(c.right)}};
    } else {
      j["corridor"] = nullptr;
    }
  }
  if (q.method == app::PredictionMethod::model) {
    j["model_id"] = optional_json(p.model_id);
    j["speed_model"] = q.use_speed_model;
  }
  if (p.table_frame) j["table_frame"] = *p.table_frame;
  // "frame" says where the trajectory is placed (world or normalised); "relative_to" what it
  // moves against: the ground, where the station knows the current, else the water.
  j["relative_to"] = p.frame;
  j["current"] = answer_current_json(p.current, p.current_source, p.current_covariance);
  j["speed_reference"] = speed_reference_json(p.motion);
  if (q.initial_yaw_rate_dps) j["initial_yaw_rate_dps"] = *q.initial_yaw_rate_dps;
  if (q.without_mission_id) j["without_mission_id"] = *q.without_mission_id;
  if (q.without_turn_id) j["without_turn_id"] = *q.without_turn_id;
  if (q.speed_after_mps) {
    j["speed_after_mps"] = *q.speed_after_mps;
    j["speed_change_source"] =
        p.speed_change_source ? json(app::to_string(*p.speed_change_source)) : json();
    j["speed_response"] = p.speed_response ? json(*p.speed_response) : json();
  }
  j["trajectory"] = points_json(p.trajectory);
  return j;
}

}  // namespace avk::server
