// The maneuver use cases over a vehicle's stored turns: the choice by CPA with each prediction
// method, the errors that name their field, and a stored turn replayed as a maneuver in progress.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/context.hpp"
#include "app/maneuvers.hpp"
#include "app/store_access.hpp"
#include "support/stored_turns.hpp"
#include "support/synthetic_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

class Maneuvers : public ::testing::Test {
 protected:
  void SetUp() override { avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 1.0, 3); }

  // Own north at 1 m/s; a contact from starboard on a collision course (both at (0, 30) at 30 s).
  app::ManeuverQuery crossing(app::PredictionMethod method) const {
    app::ManeuverQuery q;
    q.vehicle_id = "alpha";
    q.own = {0.0, 0.0, 0.0};
    q.speed_mps = 1.0;
    q.contacts = {{30.0, 30.0, 270.0, 1.0}};
    q.standoff_m = 8.0;
    q.horizon_s = 90.0;
    q.method = method;
    return q;
  }

  std::int64_t store_first_order_model() {
    store::StoredModel m;
    m.vehicle_id = "alpha";
    m.model.form = kinematics::YawModelForm::invariant;
    m.model.history = 1;
    m.model.rate_hz = 4.0;
    m.model.error_coeffs = {0.1};  // a tenth of the heading error each quarter second
    m.model.heading_coeffs = {0.0};
    return app::store_of(ctx_).models().save(m);
  }

  avk::testing::TempDb db_{"avk_app_maneuvers"};
  app::Context ctx_{db_.path()};
};

TEST_F(Maneuvers, TheTableChoosesTheSmallestTurnThatClearsItsCorridor) {
  // The corridor rule (the default is the choice by risk).
  auto q = crossing(app::PredictionMethod::avk);
  q.corridor_rule = true;
  const auto e = app::evaluate_maneuvers(ctx_, q);
  ASSERT_TRUE(e) << e.error().message;
  ASSERT_EQ(e->candidates.size(), 73u);
  EXPECT_EQ(e->table_source, "turns");
  EXPECT_TRUE(e->timed_by_turns);
  ASSERT_TRUE(e->chosen);
  const auto& c = e->candidates[*e->chosen];
  ASSERT_TRUE(c.min_edge_cpa_m);
  EXPECT_GE(*c.min_edge_cpa_m, 8.0);
  EXPECT_LE(*c.min_edge_cpa_m, c.min_cpa_m);
  for (const auto& o : e->candidates) {
    if (std::abs(o.dheading_deg) < std::abs(c.dheading_deg)) {
      EXPECT_FALSE(o.clears) << o.dheading_deg;
    }
    EXPECT_NEAR(o.path.back().t_s, 90.0, 1e-9);
    EXPECT_EQ(o.half_width_m.size(), o.path.size());
  }
  // Keeping course meets the contact.
  const auto keep = std::find_if(e->candidates.begin(), e->candidates.end(),
                                 [](const auto& o) { return o.dheading_deg == 0.0; });
  EXPECT_LT(keep->min_cpa_m, 1.0);
}

TEST_F(Maneuvers, TheInstantaneousAssumptionMovesAlongTheRayAtOnce) {
  const auto e = app::evaluate_maneuvers(ctx_, crossing(app::PredictionMethod::instantaneous));
  ASSERT_TRUE(e) << e.error().message;
  EXPECT_FALSE(e->table_source);
  for (const auto& c : e->candidates) {
    ASSERT_EQ(c.path.size(), 2u);
    EXPECT_TRUE(c.half_width_m.empty());
    const double heading = std::atan2(c.path[1].x_m, c.path[1].y_m) * 180.0 / std::numbers::pi;
    EXPECT_NEAR(std::remainder(heading - c.dheading_deg, 360.0), 0.0, 1e-6);
    EXPECT_NEAR(std::hypot(c.path[1].x_m, c.path[1].y_m), 90.0, 1e-6);
  }
  ASSERT_TRUE(e->chosen);
  // A real turn takes room: the table's choice turns at least as far as the ray's.
  const auto avk = app::evaluate_maneuvers(ctx_, crossing(app::PredictionMethod::avk));
  ASSERT_TRUE(avk && avk->chosen);
  EXPECT_GE(std::abs(avk->candidates[*avk->chosen].dheading_deg),
            std::abs(e->candidates[*e->chosen].dheading_deg));
}

TEST_F(Maneuvers, TheModelFliesEachCandidateInItsOwnTime) {
  auto q = crossing(app::PredictionMethod::model);
  const auto none = app::evaluate_maneuvers(ctx_, q);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, app::ErrorCode::not_found);
  const std::int64_t id = store_first_order_model();
  q.candidates_deg = {90.0, -90.0};
  const auto e = app::evaluate_maneuvers(ctx_, q);
  ASSERT_TRUE(e) << e.error().message;
  EXPECT_EQ(e->model_id, id);
  const auto& right = e->candidates[0].path;
  const auto& left = e->candidates[1].path;
  ASSERT_EQ(right.size(), left.size());
  for (std::size_t i = 0; i < right.size(); ++i) {
    EXPECT_NEAR(right[i].x_m, -left[i].x_m, 1e-9);
    EXPECT_NEAR(right[i].y_m, left[i].y_m, 1e-9);
  }
  EXPECT_NEAR(right[1].t_s, 0.25, 1e-12);
  // Settled on east after the turn: the last quarter-second step runs east at 1 m/s.
  const auto& a = right[right.size() - 3];
  const auto& b = right[right.size() - 2];
  EXPECT_NEAR(b.x_m - a.x_m, 0.25, 1e-3);
  EXPECT_NEAR(b.y_m - a.y_m, 0.0, 1e-3);
}

TEST_F(Maneuvers, ErrorsNameTheirField) {
  const auto field_of = [&](app::ManeuverQuery q) {
    const auto e = app::evaluate_maneuvers(ctx_, q);
    return e ? std::string("ok") : e.error().field;
  };
  auto q = crossing(app::PredictionMethod::avk);
  q.contacts.push_back({1.0, 2.0, 3.0, -1.0});
  EXPECT_EQ(field_of(q), "/contacts/1/speed_mps");
  q = crossing(app::PredictionMethod::avk);
  q.horizon_s = 0.0;
  EXPECT_EQ(field_of(q), "/horizon_s");
  q = crossing(app::PredictionMethod::avk);
  q.speed_mps = 3.0;  // the table holds 0.5 to 1.5 m/s
  EXPECT_EQ(field_of(q), "/own/speed_mps");
  q = crossing(app::PredictionMethod::avk);
  q.candidate_speed_mps = 0.1;
  EXPECT_EQ(field_of(q), "/candidate_speed_mps");
  q = crossing(app::PredictionMethod::avk);
  q.candidates_deg = {10.0, 200.0};
  EXPECT_EQ(field_of(q), "/candidates_deg/1");
  q = crossing(app::PredictionMethod::avk);
  q.standoff_m = std::nan("");
  EXPECT_EQ(field_of(q), "/standoff_m");
  q = crossing(app::PredictionMethod::avk);
  q.vehicle_id = "nobody";
  const auto e = app::evaluate_maneuvers(ctx_, q);
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, app::ErrorCode::not_found);
}

TEST_F(Maneuvers, AStoredKindOfTurnReplayedAsAManeuverInProgress) {
  // A turn like the stored ones (1 m/s, 100 deg: radius 3 m, lead-in 1.5 m), flown elsewhere.
  avk::testing::ArcTurnSpec spec;
  spec.speed_mps = 1.0;
  spec.dheading_deg = -100.0;
  spec.lead_in_m = 1.5;
  spec.radius_m = 3.0;
  spec.dt_s = 0.25;
  spec.tail_m = 4.0;
  spec.start = {5.0, 7.0, 123.0};
  const auto turn = avk::testing::make_arc_turn(spec);
  app::OngoingQuery q;
  q.vehicle_id = "alpha";
  q.start = spec.start;
  q.dheading_deg = spec.dheading_deg;
  q.speed_mps = 1.0;
  double worst = 0.0;
  for (const auto& s : turn.samples()) {
    q.elapsed_s = s.t_s - turn.samples().front().t_s;
    q.measured = kinematics::Point{s.x_m, s.y_m};
    const auto o = app::evaluate_ongoing(ctx_, q);
    ASSERT_TRUE(o) << o.error().message;
    ASSERT_TRUE(o->evaluation.deviation_m);
    worst = std::max(worst, *o->evaluation.deviation_m);
    EXPECT_EQ(o->prediction.front().x_m, 5.0);
  }
  EXPECT_LT(worst, 0.3);
  q.elapsed_s = -1.0;
  const auto bad = app::evaluate_ongoing(ctx_, q);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().field, "elapsed");
}

}  // namespace
