// Predict with a speed change (u0 -> u1), answered by the measured cells of the
// pair where it was collected, else by the constant-speed turn re-timed by the measured speed
// response; and the comparison scoring these turns held out.
#include <gtest/gtest.h>

#include <cmath>

#include "app/compare.hpp"
#include "app/context.hpp"
#include "app/predict.hpp"
#include "app/store_access.hpp"
#include "kinematics/angles.hpp"
#include "kinematics/retimed_turn.hpp"
#include "kinematics/speed_change_table.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;
namespace kin = avk::kinematics;

constexpr double kTau = 2.5;  // the stored turns' known speed response (first order)

// Speed-change turns 1.5 -> 0.75 m/s at 40 and 100 deg, two each, whose recorded speed follows
// u0 + (u1 - u0)(1 - exp(-t / kTau)); tighter than the constant-speed turns at 1.5 m/s.
void store_speed_change_turns(store::Store& db, const std::string& vid) {
  const std::int64_t mission = db.missions().create(vid, "speed changes", "{}");
  unsigned seed = 100;
  for (double d : {40.0, 100.0}) {
    for (int r = 0; r < 2; ++r) {
      avk::testing::ArcTurnSpec s;
      s.speed_mps = 1.5;
      s.dheading_deg = r ? -d : d;
      s.lead_in_m = 1.5;
      s.radius_m = 2.5 + 0.1 * r;
      s.seed = ++seed;
      s.vehicle_id = vid;
      s.mission_id = std::to_string(mission);
      // Along the analytic path at s(t), the distance the known speed profile covers.
      std::vector<kin::TurnSample> samples;
      const double total = avk::testing::arc_turn_length_m(s);
      for (int k = 0;; ++k) {
        const double t = 0.25 * k;
        const double dist = 0.75 * t + 0.75 * kTau * (1.0 - std::exp(-t / kTau));
        double h = 0.0;
        const kin::Point q = avk::testing::arc_turn_point(s, dist, &h);
        const double u = 1.5 - 0.75 * (1.0 - std::exp(-t / kTau));
        samples.push_back(
            {100.0 * seed + t, r ? -q.x_m : q.x_m, q.y_m, kin::wrap360_deg(r ? -h : h), u});
        if (dist > total) break;
      }
      kin::TurnMeta m;
      m.vehicle_id = vid;
      m.mission_id = std::to_string(mission);
      m.commanded_speed_mps = 1.5;
      m.goal_dheading_deg = s.dheading_deg;
      m.speed_after_mps = 0.75;
      kin::TurnSequence turn(m, samples);
      turn.fill_derived_metadata();
      db.turns().add(mission, turn, kin::TurnStatus::ok, "");
    }
  }
}

app::PredictQuery query(double speed, double dheading, std::optional<double> after) {
  app::PredictQuery q;
  q.vehicle_id = "sc";
  q.speed_mps = speed;
  q.dheading_deg = dheading;
  q.speed_after_mps = after;
  return q;
}

class SpeedChangePredict : public ::testing::Test {
 protected:
  void SetUp() override {
    avk::testing::store_arc_turns(app::store_of(ctx_), "sc");
    store_speed_change_turns(app::store_of(ctx_), "sc");
  }
  avk::testing::TempDb db_{"avk_app_speed_change_predict"};
  app::Context ctx_{db_.path()};
};

}  // namespace

TEST_F(SpeedChangePredict, ACollectedPairIsAnsweredByItsMeasuredCells) {
  const auto p = app::predict(ctx_, query(1.5, 100.0, 0.75));
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->speed_change_source, app::SpeedChangeSource::measured);
  const auto table =
      kin::SpeedChangeTable::build(app::store_of(ctx_).turns().load_normalized({}, "sc"));
  const auto expected = table.query(1.5, 0.75, 100.0);
  ASSERT_TRUE(expected);
  ASSERT_EQ(p->trajectory.size(), expected->trajectory.size());
  EXPECT_LT(kin::distance_m(p->trajectory.back(), expected->trajectory.back()), 1e-9);
  EXPECT_TRUE(*p->exact_cell);
  // The turns' mean radius is 2.55 m; each runs on past its arc by less than one sample.
  EXPECT_NEAR(*p->transfer_m, 2.55 * (1.0 - std::cos(kin::deg_to_rad(100.0))) + 0.2, 0.25);
  // Between its heading changes too; a left turn is reflected.
  const auto left = app::predict(ctx_, query(1.5, -70.0, 0.76));
  ASSERT_TRUE(left) << left.error().message;
  EXPECT_EQ(left->speed_change_source, app::SpeedChangeSource::measured);
  EXPECT_LT(left->trajectory.back().x_m, 0.0);
}

TEST_F(SpeedChangePredict, ElsewhereTheConstantSpeedTurnIsRetimedByTheMeasuredResponse) {
  const auto p = app::predict(ctx_, query(1.0, -100.0, 0.5));
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->speed_change_source, app::SpeedChangeSource::retimed);
  EXPECT_EQ(p->speed_response, "measured");
  const auto turns = app::store_of(ctx_).turns().load_normalized({}, "sc");
  const auto response = kin::measured_speed_response(turns);
  ASSERT_TRUE(response);
  EXPECT_NEAR(response->fraction_at(3.0), 1.0 - std::exp(-3.0 / kTau), 0.02);
  const kin::MaterializedCkt fine(kin::Ckt::build(turns));
  const auto base = fine.query(1.0, 100.0);
  const auto r = kin::retime_turn(base, 1.0, 0.5, *response);
  ASSERT_EQ(p->trajectory.size(), r.trajectory.size());
  EXPECT_NEAR(p->trajectory.back().x_m, -r.trajectory.back().x_m, 1e-9);
  EXPECT_NEAR(p->trajectory.back().y_m, r.trajectory.back().y_m, 1e-9);
  // Slowing makes the turn smaller than the constant-speed one.
  const auto constant = app::predict(ctx_, query(1.0, -100.0, std::nullopt));
  ASSERT_TRUE(constant);
  EXPECT_FALSE(constant->speed_change_source);
  EXPECT_LT(*p->transfer_m, *constant->transfer_m - 0.3);
  EXPECT_LT(kin::arc_length_m(p->trajectory), kin::arc_length_m(constant->trajectory) - 1.0);
}

TEST_F(SpeedChangePredict, TheSameSpeedAfterIsAConstantSpeedTurn) {
  const auto p = app::predict(ctx_, query(1.5, 100.0, 1.5));
  const auto c = app::predict(ctx_, query(1.5, 100.0, std::nullopt));
  ASSERT_TRUE(p && c);
  EXPECT_FALSE(p->speed_change_source);
  EXPECT_LT(kin::distance_m(p->trajectory.back(), c->trajectory.back()), 1e-12);
}

TEST_F(SpeedChangePredict, ErrorsNameSpeedAfter) {
  for (double bad : {0.0, -1.0, std::nan("")}) {
    const auto p = app::predict(ctx_, query(1.5, 100.0, bad));
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().field, "speed_after");
  }
  // A vehicle without speed-change turns and without a model has no speed response.
  avk::testing::store_arc_turns(app::store_of(ctx_), "plain");
  auto q = query(1.0, 40.0, 0.5);
  q.vehicle_id = "plain";
  const auto p = app::predict(ctx_, q);
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().field, "speed_after");
  // A model without one cannot fly it either: no model stored at all is not found.
  q.method = app::PredictionMethod::model;
  EXPECT_FALSE(app::predict(ctx_, q));
  // A CKT file holds constant-speed turns only.
  const auto file = app::predict_with_table(
      kin::Ckt::build(app::store_of(ctx_).turns().load_normalized({}, "sc")),
      query(1.0, 40.0, 0.5));
  ASSERT_FALSE(file);
  EXPECT_EQ(file.error().field, "speed_after");
}

TEST_F(SpeedChangePredict, TheComparisonScoresSpeedChangeTurnsHeldOut) {
  app::CompareQuery q;
  q.vehicle_id = "sc";
  const auto c = app::compare(ctx_, q);
  ASSERT_TRUE(c) << c.error().message;
  ASSERT_EQ(c->speed_change.size(), 2u);  // (1.5 -> 0.75) x {40, 100}
  for (const auto& cell : c->speed_change) {
    EXPECT_EQ(cell.n_turns, 2u);
    ASSERT_TRUE(cell.measured);
    ASSERT_TRUE(cell.retimed_measured);
    EXPECT_FALSE(cell.model);  // no model stored
    EXPECT_EQ(cell.measured->path_m.size(), 2u);
    // The other turn of the cell is a near copy: the measured cell predicts it best.
    EXPECT_LT(cell.measured->path().mean, 0.2);
    EXPECT_LT(cell.measured->path().mean, cell.instantaneous.path().mean);
  }
  // The constant-speed table holds none of them.
  for (const auto& cell : c->table.cells())
    for (const auto& t : cell.turns)
      EXPECT_FALSE(t.meta().speed_after_mps);
}
