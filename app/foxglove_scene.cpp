#include "app/foxglove_scene.hpp"

#include <cstdio>

#include "app/predict.hpp"

namespace avk::app::foxglove {

namespace {

std::string cell_label(const Prediction& p) {
  char text[160];
  std::snprintf(text, sizeof text, "CKT %.2f m/s %+.0f deg%s", p.query.speed_mps,
                p.query.dheading_deg, p.exact_cell.value_or(false) ? " (cell)" : " (interpolated)");
  std::string label = text;
  if (p.advance_m && p.transfer_m) {
    std::snprintf(text, sizeof text, ": advance %.1f m, transfer %.1f m", *p.advance_m,
                  *p.transfer_m);
    label += text;
  }
  return label;
}

}  // namespace

ScenePredictions scene_predictions(Context& ctx, const std::string& vehicle_id, double speed_mps,
                                   double dheading_deg, const kinematics::Pose& start) {
  ScenePredictions out;
  for (const auto method :
       {PredictionMethod::avk, PredictionMethod::model, PredictionMethod::instantaneous}) {
    PredictQuery q;
    q.vehicle_id = vehicle_id;
    q.speed_mps = speed_mps;
    q.dheading_deg = dheading_deg;
    q.method = method;
    q.pose = start;
    auto r = predict(ctx, q);
    if (!r) continue;
    if (method == PredictionMethod::avk) out.cell_label = cell_label(*r);
    out.predictions.push_back({to_string(method), std::move(r->trajectory), r->corridor});
  }
  return out;
}

}  // namespace avk::app::foxglove
