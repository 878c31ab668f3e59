#include "app/compare.hpp"

#include <algorithm>
#include <cmath>

#include "app/context.hpp"
#include "app/models.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/yaw_model.hpp"

namespace avk::app {

namespace kin = avk::kinematics;

namespace {

// Where a cell's turns started: the thesis form is not rotation invariant, so it is asked to
// predict from the course the vehicle actually held (the circular mean of the turns' initial
// headings, over the turns commanded at this speed and heading change).
double start_course_deg(const std::vector<kin::TurnSequence>& turns, double speed,
                        double dheading) {
  double sx = 0.0, sy = 0.0;
  for (const auto& t : turns) {
    if (std::abs(t.meta().commanded_speed_mps - speed) > 0.01 ||
        std::abs(std::abs(t.meta().goal_dheading_deg) - dheading) > 0.1)
      continue;
    sx += std::sin(kin::deg_to_rad(t.meta().initial_heading_deg));
    sy += std::cos(kin::deg_to_rad(t.meta().initial_heading_deg));
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
      // None stored: compared without.
      if (auto m = store_of(ctx).models().latest(q.vehicle_id)) c.model = view_of(*m);
    }
  }
  for (const auto id : q.missions)
    if (!store_of(ctx).missions().get(id)) return not_found("no mission " + std::to_string(id));
  for (const auto id : q.test_missions)
    if (!store_of(ctx).missions().get(id)) return not_found("no mission " + std::to_string(id));
  std::vector<std::int64_t> table_missions = q.missions;
  if (!q.test_missions.empty()) {
    // The table never holds a turn it is judged on.
    if (table_missions.empty()) {
      for (const auto& m : store_of(ctx).missions().list())
        if (m.vehicle_id == q.vehicle_id) table_missions.push_back(m.id);
    }
    std::erase_if(table_missions, [&](std::int64_t id) {
      return std::find(q.test_missions.begin(), q.test_missions.end(), id) != q.test_missions.end();
    });
    if (table_missions.empty())
      return invalid_argument("mission", "no mission is left to build the table from");
  }
  const auto turns = store_of(ctx).turns().load_normalized(table_missions, q.vehicle_id);
  if (turns.empty()) return not_found("no ok turns of '" + q.vehicle_id + "' to compare");
  c.table = kin::Ckt::build(turns);
  kin::TurnPredictor predictor;
  if (c.model) {
    predictor = [&](double u, double d) {
      return kin::predict_normalized_turn(c.model->model, u, d, q.completion_threshold_deg,
                                          start_course_deg(turns, u, d));
    };
  }
  c.cells = kin::compare_predictions(c.table, c.model ? &predictor : nullptr);
  if (!(q.corridor_share > 0.0 && q.corridor_share < 1.0))
    return invalid_argument("corridor", "corridor share must be within (0, 1)");
  kin::PredictiveOptions po;
  po.corridor_share = q.corridor_share;
  c.corridor_share = q.corridor_share;
  c.predictive = kin::compare_predictive(c.table, c.model ? &predictor : nullptr, po);
  {
    kin::SpeedChangePredictor model_sc;
    std::optional<kin::SpeedResponse> model_response;
    if (c.model && c.model->model.speed) {
      model_response = kin::speed_response_of_model(c.model->model);
      model_sc = [&](double u0, double u1, double d) {
        return kin::predict_normalized_turn(c.model->model, u0, d, q.completion_threshold_deg,
                                            start_course_deg(turns, u0, d), 400, true, 0.0, u1);
      };
    }
    c.speed_change =
        kin::compare_speed_changes(turns, c.table, model_response, model_sc ? &model_sc : nullptr);
  }
  if (!q.test_missions.empty()) {
    const auto test = store_of(ctx).turns().load_normalized(q.test_missions, q.vehicle_id);
    if (test.empty())
      return not_found("no ok turns of '" + q.vehicle_id + "' in the test missions");
    kin::TurnPredictor test_predictor;
    if (c.model) {
      test_predictor = [&](double u, double d) {
        return kin::predict_normalized_turn(c.model->model, u, d, q.completion_threshold_deg,
                                            start_course_deg(test, u, d));
      };
    }
    c.test_cells = kin::evaluate_table(c.table, test, c.model ? &test_predictor : nullptr, po);
  }
  return c;
}

}  // namespace avk::app
