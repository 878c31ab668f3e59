#include "app/compare.hpp"

#include <cmath>

#include "app/context.hpp"
#include "app/models.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

namespace {

// Where each cell's turns started: the thesis form is not rotation invariant, so it is asked to
// predict from the course the vehicle actually held (the circular mean of the cell's turns).
double cell_course_deg(const kin::Ckt& table, double speed, double dheading) {
  double sx = 0.0, sy = 0.0;
  for (const auto& c : table.cells()) {
    if (std::abs(c.speed_mps - speed) > 1e-9 || std::abs(c.dheading_deg - dheading) > 1e-9)
      continue;
    for (const auto& t : c.turns) {
      sx += std::sin(kin::deg_to_rad(t.meta().initial_heading_deg));
      sy += std::cos(kin::deg_to_rad(t.meta().initial_heading_deg));
    }
  }
  return sx == 0.0 && sy == 0.0 ? 0.0 : kin::heading_of_deg(sx, sy);
}

}  // namespace

Result<Comparison> compare(Context& ctx, const CompareQuery& q) {
  Comparison c;
  c.vehicle_id = q.vehicle_id;
  if (!q.without_model) {
    if (q.model_id) {
      auto m = get_model(ctx, *q.model_id);
      if (!m) return m.error();
      c.model = std::move(*m);
    } else {
      c.model = ctx.db().latest_model(q.vehicle_id);  // none stored: compared without
    }
  }
  for (const auto id : q.missions)
    if (!ctx.db().get_mission(id)) return not_found("no mission " + std::to_string(id));
  const auto turns = ctx.db().load_normalized_turns(q.missions, q.vehicle_id);
  if (turns.empty()) return not_found("no ok turns of '" + q.vehicle_id + "' to compare");
  c.table = kin::Ckt::build(turns);
  kin::TurnPredictor predictor;
  if (c.model) {
    predictor = [&](double u, double d) {
      return kin::predict_normalized_turn(c.model->model, u, d, q.completion_threshold_deg,
                                          cell_course_deg(c.table, u, d));
    };
  }
  c.cells = kin::compare_predictions(c.table, c.model ? &predictor : nullptr);
  return c;
}

}  // namespace avk::app
