// The predict use case: one rule for which table answers (the vehicle's own turns, else its own
// latest imported table), the reflection of left turns, placement at a pose, and each error with
// the parameter it names. Without HTTP or argv.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/predict.hpp"
#include "app/store_access.hpp"
#include "app/table_cache.hpp"
#include "kinematics/ckt.hpp"
#include "kinematics/ckt_file.hpp"
#include "kinematics/maneuver.hpp"
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  const auto p = app::predict(ctx_, query("alpha", 1.0, 100.0));
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->table_source, "turns");
  EXPECT_FALSE(p->snapshot_id);
  // The same table built here, independently of the cache.
  const auto table =
      kinematics::Ckt::build(app::store_of(ctx_).turns().load_normalized({}, "alpha"));
  const kinematics::MaterializedCkt fine(table);
  const auto expected = fine.query(1.0, 100.0);
  expect_same_line(p->trajectory, expected.trajectory);
  EXPECT_DOUBLE_EQ(*p->advance_m, expected.advance_m);
  EXPECT_DOUBLE_EQ(*p->transfer_m, expected.transfer_m);
  // A right turn of 100 deg ends right of the start, heading past east.
  EXPECT_GT(p->trajectory.back().x_m, 1.0);
}

TEST_F(Predict, SaysWhenOneCellAnswersAndWhenTheTableIsExtrapolated) {
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");  // heading changes 40, 100, 160 deg
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");  // heading changes 40, 100, 160 deg
  const auto table =
      kinematics::Ckt::build(app::store_of(ctx_).turns().load_normalized({}, "alpha"));
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "donor", 1.5);
  kinematics::Ckt table =
      kinematics::Ckt::build(app::store_of(ctx_).turns().load_normalized({}, "donor"));
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "small", 1.0);
  avk::testing::store_arc_turns(app::store_of(ctx_), "large", 2.0);
  // A table imported last, for a third vehicle, must not answer for the others.
  kinematics::Ckt other =
      kinematics::Ckt::build(app::store_of(ctx_).turns().load_normalized({}, "small"));
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
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
  // A heading change out of range and a speed beyond the table's: both named, the
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
  const auto tight = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 1.0);
  const auto wide = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 2.0);
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
        kinematics::Ckt::build(app::store_of(ctx_).turns().load_normalized({mission}, "alpha")), q);
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
  const auto only = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
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
  const auto a = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  const auto b = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 2.0);
  const auto save = [&](std::vector<std::int64_t> missions) {
    store::StoredModel m;
    m.vehicle_id = "alpha";
    m.training_missions = std::move(missions);
    m.model.form = kinematics::YawModelForm::invariant;
    m.model.history = 1;
    m.model.rate_hz = 4.0;
    m.model.error_coeffs = {0.1};
    m.model.heading_coeffs = {0.0};
    return app::store_of(ctx_).models().save(m);
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

// The id of the first stored turn of the mission in a cell; 0 when it has none.
std::int64_t first_turn_in_cell(app::Context& ctx, std::int64_t mission, double speed_mps,
                                double dheading_deg) {
  store::TurnFilter f;
  f.mission_id = mission;
  f.speed_mps = speed_mps;
  f.dheading_deg = dheading_deg;
  const auto rows = app::store_of(ctx).turns().list(f);
  return rows.empty() ? 0 : rows.front().id;
}

// Live's fair prediction of the turn just finished: every other turn of the vehicle.
TEST_F(Predict, WithoutATurnTheTableHoldsEveryOtherTurn) {
  const auto mission = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 1.0, 3);
  avk::testing::store_arc_turns(app::store_of(ctx_), "beta");
  const std::int64_t turn = first_turn_in_cell(ctx_, mission, 1.0, 100.0);
  ASSERT_GT(turn, 0);
  const auto all = app::store_of(ctx_).turns().load_normalized({}, "alpha");
  store::TurnsLeftOut left_out;
  left_out.turn_id = turn;
  const auto others = app::store_of(ctx_).turns().load_normalized(
      {}, "alpha", false, store::TurnFrameChoice::ground, left_out);
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
  q.without_turn_id = app::store_of(ctx_).turns().list({}).back().id;  // beta's
  const auto foreign = app::predict(ctx_, q);
  ASSERT_FALSE(foreign);
  EXPECT_EQ(foreign.error().field, "without_turn");
  EXPECT_NE(foreign.error().message.find("belongs to vehicle 'beta', not 'alpha'"),
            std::string::npos)
      << foreign.error().message;
}

// The held-out table is kept between requests (app::TableCache::held_out): asked again, the same
// answer; once the vehicle has a new turn in the cell, an answer that counts it.
TEST_F(Predict, AHeldOutAnswerIsTheSameWhenAskedAgainAndFollowsANewTurn) {
  const auto mission = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 1.0, 3);
  auto q = query("alpha", 1.0, 100.0);
  q.without_turn_id = first_turn_in_cell(ctx_, mission, 1.0, 100.0);
  ASSERT_GT(*q.without_turn_id, 0);
  const auto first = app::predict(ctx_, q);
  ASSERT_TRUE(first && first->corridor) << first.error().message;
  EXPECT_EQ(first->corridor->n_turns, 2u);
  const auto second = app::predict(ctx_, q);
  ASSERT_TRUE(second);
  expect_same_line(second->trajectory, first->trajectory);
  EXPECT_EQ(second->advance_m, first->advance_m);

  avk::testing::store_one_arc_turn(app::store_of(ctx_), mission, "alpha", 1.0, 100.0);
  // The station re-reads the store at most once a second: wait for the answer that counts it.
  std::size_t counted = 0;
  for (const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
       counted != 3u && std::chrono::steady_clock::now() < deadline;) {
    const auto p = app::predict(ctx_, q);
    ASSERT_TRUE(p && p->corridor);
    counted = p->corridor->n_turns;
    if (counted != 3u) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(counted, 3u);
}

// --- in a current: over ground by default ---------------------------------------------------

// The station's estimate for the vehicle: `east`, `north` with a 1-sigma of `sd` m/s on each.
void store_current(store::Store& db, std::int64_t mission, double east, double north, double sd) {
  store::StoredCurrent c;
  c.mission_id = mission;
  c.t_s = 100.0;
  c.estimate.east_mps = east;
  c.estimate.north_mps = north;
  c.estimate.covariance = {sd * sd, 0.0, sd * sd};
  c.estimate.legs = 6;
  db.currents().save(c, {});
}

app::PredictQuery ray_east(kinematics::WaterCurrent c, std::optional<bool> over_ground) {
  auto q = query("anyone", 1.0, 90.0);
  q.method = app::PredictionMethod::instantaneous;
  q.pose = kinematics::Pose{0.0, 0.0, 0.0};  // heading north, the ray due east for 20 s
  q.current = c;
  q.speed_over_ground = over_ground;
  return q;
}

// A straight leg at 1 m/s through the water for 20 s in a current along it, against it and
// across it. Held through the water it is carried c·20 s; held over ground the loop makes 1 m/s
// good over ground, so the leg takes 20/k s (k the scale of the speed through the water) and
// covers 20/k m: along 0.2 m/s, k = 0.8 and 25 m; against it, k = 1.2 and 16.67 m; across it,
// k = sqrt(0.96) and 20 m along plus 0.2·20/k across.
TEST_F(Predict, AStraightLegInACurrentIsCarriedOrRetimedAsTheSpeedLoopHoldsIt) {
  struct Case {
    kinematics::WaterCurrent c;
    kinematics::Point water, ground;
  };
  const double k_cross = std::sqrt(0.96);
  for (const Case& c : {Case{{0.2, 0.0}, {24.0, 0.0}, {25.0, 0.0}},
                        Case{{-0.2, 0.0}, {16.0, 0.0}, {20.0 - 0.2 * 20.0 / 1.2, 0.0}},
                        Case{{0.0, 0.2}, {20.0, 4.0}, {20.0, 0.2 * 20.0 / k_cross}}}) {
    const auto water = app::predict(ctx_, ray_east(c.c, false));
    const auto ground = app::predict(ctx_, ray_east(c.c, true));
    ASSERT_TRUE(water && ground);
    EXPECT_NEAR(water->trajectory.back().x_m, c.water.x_m, 1e-9);
    EXPECT_NEAR(water->trajectory.back().y_m, c.water.y_m, 1e-9);
    EXPECT_NEAR(ground->trajectory.back().x_m, c.ground.x_m, 1e-9);
    EXPECT_NEAR(ground->trajectory.back().y_m, c.ground.y_m, 1e-9);
    // Both are over ground (a current was given), and say which reference carried them.
    for (const auto* p : {&*water, &*ground}) {
      EXPECT_EQ(p->frame, "ground");
      EXPECT_EQ(p->current_source, "query");
      EXPECT_EQ(p->motion.speed_reference_source, "query");
    }
    EXPECT_FALSE(water->motion.speed_over_ground);
    EXPECT_TRUE(ground->motion.speed_over_ground);
  }
  // Unasked, the reference is the vehicle's (the default until the station identifies it: over
  // ground, as the M200's loop holds it).
  const auto unasked = app::predict(ctx_, ray_east({0.2, 0.0}, std::nullopt));
  ASSERT_TRUE(unasked);
  EXPECT_EQ(unasked->motion.speed_reference_source, "default");
  EXPECT_TRUE(unasked->motion.speed_over_ground);
  EXPECT_NEAR(unasked->trajectory.back().x_m, 25.0, 1e-9);
}

// A turn in a current, held over ground: each segment of the answer makes good over ground the
// speed it has through the water, and differs from the path through the water by c·t over its
// re-timed time. Held through the water: the path through the water plus c·t at the table's own
// times. Either way the answer starts where the turn does and the vertices stay one for one.
TEST_F(Predict, ATurnInACurrentKeepsItsStillWaterSpeedOverGroundWhenTheLoopHoldsIt) {
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  const kinematics::WaterCurrent c{0.15, -0.1};
  auto q = query("alpha", 1.0, 100.0);
  q.no_current = true;
  const auto through_water = app::predict(ctx_, q);
  q.no_current = false;
  q.current = c;
  q.speed_over_ground = true;
  const auto over_ground = app::predict(ctx_, q);
  q.speed_over_ground = false;
  const auto carried = app::predict(ctx_, q);
  ASSERT_TRUE(through_water && over_ground && carried);
  EXPECT_EQ(through_water->frame, "water");
  EXPECT_EQ(through_water->current_source, "none");
  EXPECT_FALSE(through_water->current);
  // The water path's times, as the table recorded its turns.
  const auto table =
      kinematics::Ckt::build(app::store_of(ctx_).turns().load_normalized({}, "alpha"));
  const auto fine = kinematics::MaterializedCkt(table).query(1.0, 100.0);
  ASSERT_TRUE(fine.timing);
  const kinematics::TimedPath water =
      kinematics::timed_maneuver(0.0, 1.0, through_water->trajectory, fine.timing).path;
  const auto& g = over_ground->trajectory;
  const auto& d = carried->trajectory;
  ASSERT_EQ(g.size(), water.size());
  ASSERT_EQ(d.size(), water.size());
  EXPECT_NEAR(g.front().x_m, 0.0, 1e-12);
  EXPECT_NEAR(g.front().y_m, 0.0, 1e-12);
  const double cs = std::hypot(c.east_mps, c.north_mps);
  double t_ground = 0.0;
  std::size_t moving = 0;
  for (std::size_t i = 1; i < water.size(); ++i) {
    const double dt = water[i].t_s - water[i - 1].t_s;
    const double wx = water[i].x_m - water[i - 1].x_m, wy = water[i].y_m - water[i - 1].y_m;
    // Carried: the water path plus c·t at the table's times.
    EXPECT_NEAR(d[i].x_m, water[i].x_m + c.east_mps * water[i].t_s, 1e-9) << i;
    EXPECT_NEAR(d[i].y_m, water[i].y_m + c.north_mps * water[i].t_s, 1e-9) << i;
    const double gx = g[i].x_m - g[i - 1].x_m, gy = g[i].y_m - g[i - 1].y_m;
    // The drift over the segment is along c, c times its time over ground...
    const double drift = std::hypot(gx - wx, gy - wy);
    const double dt_ground = drift / cs;
    EXPECT_NEAR((gx - wx) * cs, c.east_mps * drift, 1e-9) << i;
    EXPECT_NEAR((gy - wy) * cs, c.north_mps * drift, 1e-9) << i;
    t_ground += dt_ground;
    // ...which puts point i on the water path plus the drift over the re-timed time so far...
    EXPECT_NEAR(g[i].x_m, water[i].x_m + c.east_mps * t_ground, 1e-6) << i;
    EXPECT_NEAR(g[i].y_m, water[i].y_m + c.north_mps * t_ground, 1e-6) << i;
    // ...and in that time the segment makes good its still-water speed over ground (a segment
    // far slower than the current would need a speed through the water beyond the loop's bounds).
    if (!(dt > 1e-6) || std::hypot(wx, wy) < 2.0 * cs * dt) continue;
    ++moving;
    EXPECT_NEAR(std::hypot(gx, gy) / dt_ground, std::hypot(wx, wy) / dt, 1e-6) << i;
  }
  EXPECT_GT(moving, 5u);
  // The two references differ measurably by the end of the turn.
  EXPECT_GT(std::hypot(g.back().x_m - d.back().x_m, g.back().y_m - d.back().y_m), 0.05);
}

// Not asked for a current, the answer is over ground wherever the station knows it: the stored
// estimate when it is told apart from still water (with its uncertainty), still water when it is
// not; through the water only without an estimate, or when asked with current=none.
TEST_F(Predict, UnaskedTheAnswerIsOverGroundWithTheStoredEstimate) {
  const std::int64_t mission = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  auto q = query("alpha", 1.0, 100.0);
  q.pose = kinematics::Pose{10.0, -5.0, 30.0};
  const auto before = app::predict(ctx_, q);  // no estimate yet
  ASSERT_TRUE(before);
  EXPECT_EQ(before->frame, "water");
  EXPECT_EQ(before->current_source, "unknown");
  EXPECT_FALSE(before->current);

  store_current(app::store_of(ctx_), mission, 0.0, -0.2, 0.01);
  const auto by_default = app::predict(ctx_, q);
  auto given = q;
  given.current = kinematics::WaterCurrent{0.0, -0.2};
  const auto as_given = app::predict(ctx_, given);
  auto none = q;
  none.no_current = true;
  const auto through_water = app::predict(ctx_, none);
  ASSERT_TRUE(by_default && as_given && through_water);
  EXPECT_EQ(by_default->frame, "ground");
  EXPECT_EQ(by_default->current_source, "live");
  ASSERT_TRUE(by_default->current);
  EXPECT_DOUBLE_EQ(by_default->current->north_mps, -0.2);
  ASSERT_TRUE(by_default->current_covariance);
  EXPECT_DOUBLE_EQ((*by_default->current_covariance)[0], 1e-4);
  EXPECT_DOUBLE_EQ((*by_default->current_covariance)[2], 1e-4);
  expect_same_line(by_default->trajectory, as_given->trajectory);
  // current=none: the path through the water, the same as before there was an estimate.
  EXPECT_EQ(through_water->frame, "water");
  EXPECT_EQ(through_water->current_source, "none");
  EXPECT_FALSE(through_water->current);
  expect_same_line(through_water->trajectory, before->trajectory);
  // Carried south by the current: the end lies south of the one through the water.
  EXPECT_LT(by_default->trajectory.back().y_m, through_water->trajectory.back().y_m - 1.0);

  // An estimate not told apart from still water: over ground, nothing added.
  store_current(app::store_of(ctx_), mission, 0.01, 0.0, 0.02);
  const auto still = app::predict(ctx_, q);
  ASSERT_TRUE(still);
  EXPECT_EQ(still->frame, "ground");
  EXPECT_EQ(still->current_source, "still_water");
  EXPECT_FALSE(still->current);
  ASSERT_TRUE(still->current_covariance);
  expect_same_line(still->trajectory, before->trajectory);
}

// A CKT file has no station: a given current is applied over ground with the asked reference
// (else the default), and without one the answer is through the water.
TEST_F(Predict, ATableFileAppliesAGivenCurrentWithTheAskedSpeedReference) {
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  const auto table =
      kinematics::Ckt::build(app::store_of(ctx_).turns().load_normalized({}, "alpha"));
  app::PredictQuery q = query("alpha", 1.0, 100.0);
  const auto plain = app::predict_with_table(table, q);
  q.current = kinematics::WaterCurrent{0.2, 0.0};
  const auto default_ref = app::predict_with_table(table, q);
  q.speed_over_ground = true;
  const auto over_ground = app::predict_with_table(table, q);
  q.speed_over_ground = false;
  const auto carried = app::predict_with_table(table, q);
  ASSERT_TRUE(plain && default_ref && over_ground && carried);
  EXPECT_EQ(plain->frame, "water");
  EXPECT_EQ(over_ground->frame, "ground");
  EXPECT_EQ(default_ref->motion.speed_reference_source, "default");
  EXPECT_EQ(over_ground->motion.speed_reference_source, "query");
  EXPECT_FALSE(carried->motion.speed_over_ground);
  expect_same_line(default_ref->trajectory, over_ground->trajectory);
  EXPECT_GT(std::abs(over_ground->trajectory.back().x_m - carried->trajectory.back().x_m), 0.05);
}

TEST(PredictMethod, NamesRoundTrip) {
  for (const auto m : {app::PredictionMethod::avk, app::PredictionMethod::model,
                       app::PredictionMethod::instantaneous})
    EXPECT_EQ(app::prediction_method_from_string(app::to_string(m)), m);
  EXPECT_FALSE(app::prediction_method_from_string("guess"));
}

}  // namespace
