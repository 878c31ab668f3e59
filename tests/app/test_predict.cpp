// The predict use case: one rule for which table answers (the vehicle's own turns, else its own
// latest imported table), the reflection of left turns, placement at a pose, and each error with
// the parameter it names. Without HTTP or argv.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/predict.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/yaw_model.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

app::PredictQuery query(const std::string& vid, double speed, double dheading) {
  app::PredictQuery q;
  q.vehicle_id = vid;
  q.speed_mps = speed;
  q.dheading_deg = dheading;
  return q;
}

void expect_same_line(const kinematics::Polyline& a, const kinematics::Polyline& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_DOUBLE_EQ(a[i].x_m, b[i].x_m) << i;
    EXPECT_DOUBLE_EQ(a[i].y_m, b[i].y_m) << i;
  }
}

class Predict : public ::testing::Test {
 protected:
  avk::testing::TempDb db_{"avk_app_predict"};
  app::Context ctx_{db_.path()};
};

TEST_F(Predict, AvkAnswersFromTheVehiclesOwnTurnsThroughTheFineTable) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");
  const auto p = app::predict(ctx_, query("alpha", 1.0, 100.0));
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->table_source, "turns");
  EXPECT_FALSE(p->snapshot_id);
  // The same table built here, independently of the cache.
  const auto table = kinematics::Ckt::build(ctx_.db().load_normalized_turns({}, "alpha"));
  const kinematics::MaterializedCkt fine(table);
  const auto expected = fine.query(1.0, 100.0);
  expect_same_line(p->trajectory, expected.trajectory);
  EXPECT_DOUBLE_EQ(*p->advance_m, expected.advance_m);
  EXPECT_DOUBLE_EQ(*p->transfer_m, expected.transfer_m);
  // A right turn of 100 deg ends right of the start, heading past east.
  EXPECT_GT(p->trajectory.back().x_m, 1.0);
}

TEST_F(Predict, SaysWhenOneCellAnswersAndWhenTheTableIsExtrapolated) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");  // heading changes 40, 100, 160 deg
  const auto exact = app::predict(ctx_, query("alpha", 1.0, 100.0));
  const auto between = app::predict(ctx_, query("alpha", 1.0, 70.0));
  const auto beyond = app::predict(ctx_, query("alpha", 1.0, -175.0));
  ASSERT_TRUE(exact && between && beyond);
  EXPECT_EQ(exact->exact_cell, true);
  EXPECT_EQ(exact->extrapolated, false);
  EXPECT_EQ(between->exact_cell, false);
  EXPECT_EQ(between->extrapolated, false);
  EXPECT_EQ(beyond->extrapolated, true);
  EXPECT_LT(beyond->trajectory.back().x_m, 0.0);  // a left turn
}

// Between the fine table's rows (0.75 m/s) the answer is blended, not the 0.8 m/s row's, and its
// flags say what the table's own query says.
TEST_F(Predict, ASpeedBetweenFineRowsIsInterpolatedAndFlaggedAsTheTableWould) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");  // heading changes 40, 100, 160 deg
  const auto table = kinematics::Ckt::build(ctx_.db().load_normalized_turns({}, "alpha"));
  for (const auto& [u, d] : {std::pair{0.75, 100.0}, std::pair{1.25, -55.5}, std::pair{0.83, 175.5},
                             std::pair{1.0, 100.0}}) {
    const auto p = app::predict(ctx_, query("alpha", u, d));
    ASSERT_TRUE(p) << p.error().message;
    const kinematics::TurnPrediction truth = table.query(u, d);
    EXPECT_NEAR(*p->advance_m, truth.advance_m, 0.01) << u << " " << d;
    EXPECT_NEAR(*p->transfer_m, truth.transfer_m, 0.01) << u << " " << d;
    EXPECT_LT(kinematics::distance_m(p->trajectory.back(), truth.trajectory.back()), 0.1);
    EXPECT_EQ(p->exact_cell, truth.exact_cell) << u << " " << d;
    EXPECT_EQ(p->extrapolated, truth.extrapolated) << u << " " << d;
  }
  EXPECT_EQ(app::predict(ctx_, query("alpha", 1.0, 100.0))->exact_cell, true);
  EXPECT_EQ(app::predict(ctx_, query("alpha", 0.75, 100.0))->exact_cell, false);
  EXPECT_EQ(app::predict(ctx_, query("alpha", 0.83, 175.5))->extrapolated, true);
}

TEST_F(Predict, ALeftTurnIsTheMirrorImageOfTheRightOne) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");
  for (const auto method : {app::PredictionMethod::avk, app::PredictionMethod::instantaneous}) {
    auto right_q = query("alpha", 1.2, 70.0);
    auto left_q = query("alpha", 1.2, -70.0);
    right_q.method = left_q.method = method;
    const auto right = app::predict(ctx_, right_q);
    const auto left = app::predict(ctx_, left_q);
    ASSERT_TRUE(right && left);
    ASSERT_EQ(right->trajectory.size(), left->trajectory.size());
    for (std::size_t i = 0; i < right->trajectory.size(); ++i) {
      EXPECT_DOUBLE_EQ(left->trajectory[i].x_m, -right->trajectory[i].x_m);
      EXPECT_DOUBLE_EQ(left->trajectory[i].y_m, right->trajectory[i].y_m);
    }
  }
}

TEST_F(Predict, APoseRotatesAndTranslatesTheNormalisedTurn) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");
  auto q = query("alpha", 1.0, 40.0);
  const auto normal = app::predict(ctx_, q);
  q.pose = kinematics::Pose{100.0, -20.0, 90.0};  // heading east
  const auto placed = app::predict(ctx_, q);
  ASSERT_TRUE(normal && placed);
  ASSERT_EQ(normal->trajectory.size(), placed->trajectory.size());
  for (std::size_t i = 0; i < normal->trajectory.size(); ++i) {
    // North becomes east, east becomes south.
    EXPECT_NEAR(placed->trajectory[i].x_m, 100.0 + normal->trajectory[i].y_m, 1e-9);
    EXPECT_NEAR(placed->trajectory[i].y_m, -20.0 - normal->trajectory[i].x_m, 1e-9);
  }
}

TEST_F(Predict, InstantaneousIsARayOnTheNewHeading) {
  auto q = query("anyone", 1.5, 90.0);
  q.method = app::PredictionMethod::instantaneous;
  const auto p = app::predict(ctx_, q);
  ASSERT_TRUE(p);
  ASSERT_EQ(p->trajectory.size(), 2u);
  EXPECT_NEAR(p->trajectory[1].x_m, 30.0, 1e-9);  // 20 s at 1.5 m/s, due east
  EXPECT_NEAR(p->trajectory[1].y_m, 0.0, 1e-9);
}

TEST_F(Predict, AVehicleWithOnlyAnImportedTableIsAnsweredByIt) {
  avk::testing::store_arc_turns(ctx_.db(), "donor", 1.5);
  kinematics::Ckt table = kinematics::Ckt::build(ctx_.db().load_normalized_turns({}, "donor"));
  table.vehicle_id = "bravo";
  const auto imported = app::import_ckt(ctx_, "bravo", kinematics::ckt_to_json_string(table));
  ASSERT_TRUE(imported) << imported.error().message;
  const auto p = app::predict(ctx_, query("bravo", 1.0, 100.0));
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->table_source, "imported");
  EXPECT_EQ(p->snapshot_id, imported->snapshot_id);
  const kinematics::MaterializedCkt fine(
      kinematics::parse_ckt_json(kinematics::ckt_to_json_string(table)));
  expect_same_line(p->trajectory, fine.query(1.0, 100.0).trajectory);
}

TEST_F(Predict, EachVehicleOfADatabaseIsAnsweredByItsOwnTable) {
  avk::testing::store_arc_turns(ctx_.db(), "small", 1.0);
  avk::testing::store_arc_turns(ctx_.db(), "large", 2.0);
  // A table imported last, for a third vehicle, must not answer for the others.
  kinematics::Ckt other = kinematics::Ckt::build(ctx_.db().load_normalized_turns({}, "small"));
  other.vehicle_id = "third";
  ASSERT_TRUE(app::import_ckt(ctx_, "third", kinematics::ckt_to_json_string(other)));
  const auto small = app::predict(ctx_, query("small", 1.0, 100.0));
  const auto large = app::predict(ctx_, query("large", 1.0, 100.0));
  ASSERT_TRUE(small && large);
  // Twice the lead-in and radius: about twice the advance and transfer.
  EXPECT_NEAR(*large->advance_m / *small->advance_m, 2.0, 0.1);
  EXPECT_NEAR(*large->transfer_m / *small->transfer_m, 2.0, 0.1);
  const auto none = app::predict(ctx_, query("nobody", 1.0, 100.0));
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, app::ErrorCode::not_found);
}

TEST_F(Predict, BadQuestionsNameTheirParameter) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");
  const auto field_of = [&](app::PredictQuery q) {
    const auto r = app::predict(ctx_, q);
    EXPECT_FALSE(r);
    EXPECT_EQ(r.error().code, app::ErrorCode::invalid_argument);
    return r.error().field;
  };
  EXPECT_EQ(field_of(query("alpha", 0.0, 40.0)), "speed");
  EXPECT_EQ(field_of(query("alpha", NAN, 40.0)), "speed");
  EXPECT_EQ(field_of(query("alpha", 1.0, 0.0)), "dheading");
  EXPECT_EQ(field_of(query("alpha", 1.0, 181.0)), "dheading");
  EXPECT_EQ(field_of(query("alpha", 3.5, 40.0)), "speed");  // beyond the table's speeds
  // Issue 19: a heading change out of range and a speed beyond the table's: both named, the
  // speed with the table's range.
  const auto both = app::predict(ctx_, query("alpha", 3.5, 181.0));
  ASSERT_FALSE(both);
  ASSERT_EQ(both.error().fields.size(), 2u) << both.error().message;
  EXPECT_EQ(both.error().fields[0].field, "speed");
  EXPECT_NE(both.error().fields[0].message.find("outside the table's speed range ["),
            std::string::npos)
      << both.error().fields[0].message;
  EXPECT_EQ(both.error().fields[1].field, "dheading");
  auto m = query("alpha", 1.0, 40.0);
  m.method = app::PredictionMethod::model;
  const auto no_model = app::predict(ctx_, m);
  ASSERT_FALSE(no_model);
  EXPECT_EQ(no_model.error().code, app::ErrorCode::not_found);
  m.model_id = 77;
  EXPECT_NE(app::predict(ctx_, m).error().message.find("no model 77"), std::string::npos);
}

// Replay's fair prediction: a past turn predicted by what never saw its mission.
TEST_F(Predict, WithoutAMissionTheTableHoldsOnlyTheOtherMissionsTurns) {
  const auto tight = avk::testing::store_arc_turns(ctx_.db(), "alpha", 1.0);
  const auto wide = avk::testing::store_arc_turns(ctx_.db(), "alpha", 2.0);
  const auto held_out = [&](std::int64_t mission) {
    auto q = query("alpha", 1.0, -100.0);
    q.without_mission_id = mission;
    q.pose = kinematics::Pose{5.0, -3.0, 30.0};
    return app::predict(ctx_, q);
  };
  const auto table_of = [&](std::int64_t mission) {
    auto q = query("alpha", 1.0, -100.0);
    q.pose = kinematics::Pose{5.0, -3.0, 30.0};
    return app::predict_with_table(
        kinematics::Ckt::build(ctx_.db().load_normalized_turns({mission}, "alpha")), q);
  };
  const auto without_tight = held_out(tight);
  const auto without_wide = held_out(wide);
  ASSERT_TRUE(without_tight && without_wide) << without_tight.error().message;
  const auto only_wide = table_of(wide);
  const auto only_tight = table_of(tight);
  ASSERT_TRUE(only_wide && only_tight);
  expect_same_line(without_tight->trajectory, only_wide->trajectory);
  expect_same_line(without_wide->trajectory, only_tight->trajectory);
  EXPECT_DOUBLE_EQ(*without_tight->advance_m, *only_wide->advance_m);
  EXPECT_EQ(without_tight->table_source, "turns");
  // The two missions turn differently (radii 3 m and 6 m at 1 m/s): leaving one out matters.
  EXPECT_GT(*without_tight->advance_m - *without_wide->advance_m, 1.0);
}

TEST_F(Predict, WithoutAMissionNamesWhatIsMissing) {
  const auto only = avk::testing::store_arc_turns(ctx_.db(), "alpha");
  auto q = query("alpha", 1.0, 100.0);
  q.without_mission_id = only;
  const auto none_left = app::predict(ctx_, q);
  ASSERT_FALSE(none_left);
  EXPECT_EQ(none_left.error().code, app::ErrorCode::not_found);
  EXPECT_NE(none_left.error().message.find("no ok turns outside mission " + std::to_string(only)),
            std::string::npos)
      << none_left.error().message;
  q.without_mission_id = 999;
  EXPECT_NE(app::predict(ctx_, q).error().message.find("no mission 999"), std::string::npos);
  q.without_mission_id = only;
  q.initial_yaw_rate_dps = 5.0;
  const auto spinning = app::predict(ctx_, q);
  ASSERT_FALSE(spinning);
  EXPECT_EQ(spinning.error().field, "without_mission");
}

TEST_F(Predict, WithoutAMissionTheModelIsOneNotTrainedOnIt) {
  const auto a = avk::testing::store_arc_turns(ctx_.db(), "alpha");
  const auto b = avk::testing::store_arc_turns(ctx_.db(), "alpha", 2.0);
  const auto save = [&](std::vector<std::int64_t> missions) {
    store::StoredModel m;
    m.vehicle_id = "alpha";
    m.training_missions = std::move(missions);
    m.model.form = kinematics::YawModelForm::invariant;
    m.model.history = 1;
    m.model.rate_hz = 4.0;
    m.model.error_coeffs = {0.1};
    m.model.heading_coeffs = {0.0};
    return ctx_.db().save_model(m);
  };
  const auto on_b = save({b});
  const auto on_both = save({a, b});  // the latest
  auto q = query("alpha", 1.0, 100.0);
  q.method = app::PredictionMethod::model;
  ASSERT_EQ(app::predict(ctx_, q)->model_id, on_both);
  q.without_mission_id = a;
  const auto fair = app::predict(ctx_, q);
  ASSERT_TRUE(fair) << fair.error().message;
  EXPECT_EQ(fair->model_id, on_b);
  q.model_id = on_both;
  const auto asked = app::predict(ctx_, q);
  ASSERT_FALSE(asked);
  EXPECT_EQ(asked.error().field, "model");
  q.model_id.reset();
  q.without_mission_id = b;
  const auto none = app::predict(ctx_, q);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, app::ErrorCode::not_found);
}

// Live's fair prediction of the turn just finished: every other turn of the vehicle.
TEST_F(Predict, WithoutATurnTheTableHoldsEveryOtherTurn) {
  const auto mission = avk::testing::store_arc_turns(ctx_.db(), "alpha", 1.0, 3);
  avk::testing::store_arc_turns(ctx_.db(), "beta");
  store::TurnFilter f;
  f.mission_id = mission;
  f.speed_mps = 1.0;
  f.dheading_deg = 100.0;
  const auto rows = ctx_.db().list_turns(f);
  ASSERT_FALSE(rows.empty());
  const std::int64_t turn = rows.front().id;
  const auto all = ctx_.db().load_normalized_turns({}, "alpha");
  store::TurnsLeftOut left_out;
  left_out.turn_id = turn;
  const auto others =
      ctx_.db().load_normalized_turns({}, "alpha", false, store::TurnFrameChoice::ground, left_out);
  ASSERT_EQ(others.size() + 1, all.size());

  auto q = query("alpha", 1.0, 100.0);
  q.without_turn_id = turn;
  const auto fair = app::predict(ctx_, q);
  ASSERT_TRUE(fair) << fair.error().message;
  const auto expected =
      app::predict_with_table(kinematics::Ckt::build(others), query("alpha", 1.0, 100.0));
  ASSERT_TRUE(expected);
  expect_same_line(fair->trajectory, expected->trajectory);
  // The cell that answers holds one turn fewer: its corridor counts two, not three.
  ASSERT_TRUE(fair->corridor.has_value());
  EXPECT_EQ(fair->corridor->n_turns, 2u);
  const auto full = app::predict(ctx_, query("alpha", 1.0, 100.0));
  ASSERT_TRUE(full && full->corridor.has_value());
  EXPECT_EQ(full->corridor->n_turns, 3u);

  q.without_turn_id = 9999;
  EXPECT_NE(app::predict(ctx_, q).error().message.find("no turn 9999"), std::string::npos);
  q.without_turn_id = ctx_.db().list_turns({}).back().id;  // beta's
  const auto foreign = app::predict(ctx_, q);
  ASSERT_FALSE(foreign);
  EXPECT_EQ(foreign.error().field, "without_turn");
  EXPECT_NE(foreign.error().message.find("belongs to vehicle 'beta', not 'alpha'"),
            std::string::npos)
      << foreign.error().message;
}

TEST(PredictMethod, NamesRoundTrip) {
  for (const auto m : {app::PredictionMethod::avk, app::PredictionMethod::model,
                       app::PredictionMethod::instantaneous})
    EXPECT_EQ(app::prediction_method_from_string(app::to_string(m)), m);
  EXPECT_FALSE(app::prediction_method_from_string("guess"));
}

}  // namespace
