#include "app/foxglove_scene.hpp"

#include <cmath>
#include <cstdio>

#include "app/predict.hpp"
#include "kinematics/angles.hpp"

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

// The current a prediction was carried by, as read; else why it was not.
std::string current_text(const Prediction& p) {
  const std::string source = p.current_source.value_or("none");
  if (!p.current) return source == "still_water" ? "still water" : source;
  const double speed = std::hypot(p.current->east_mps, p.current->north_mps);
  char text[120];
  std::snprintf(text, sizeof text, "%.2f m/s toward %.0f deg (%s)", speed,
                kinematics::heading_of_deg(p.current->east_mps, p.current->north_mps),
                source.c_str());
  return text;
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
    // The station's default, as every front end asks it: over ground where the current is known.
    out.predictions.push_back(
        {to_string(method), std::move(r->trajectory), r->corridor, r->frame, current_text(*r)});
  }
  return out;
}

}  // namespace avk::app::foxglove
