// The yaw model and the comparison through the use cases: a fit stored with its provenance,
// refused for missions of another vehicle; the history sweep; a model's view of a mission; the
// comparison with and without a model. Without HTTP or argv.
#include <gtest/gtest.h>

#include <cmath>

#include "app/compare.hpp"
#include "app/context.hpp"
#include "app/models.hpp"
#include "app/predict.hpp"
#include "support/recorded_mission.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

class Models : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    db_ = new avk::testing::TempDb("avk_app_models");
    store::Store db(db_->path());
    mission_ = avk::testing::run_recorded_mission(db, "sim-a");
    second_ = avk::testing::run_recorded_mission(db, "sim-a");
    foreign_ = avk::testing::run_recorded_mission(db, "sim-b");
  }
  static void TearDownTestSuite() { delete db_; }
  static kinematics::IdentificationOptions options() {
    kinematics::IdentificationOptions o;
    o.history_s = 3.0;
    return o;
  }
  static avk::testing::TempDb* db_;
  static std::int64_t mission_, second_, foreign_;
  app::Context ctx_{db_->path()};
};
avk::testing::TempDb* Models::db_ = nullptr;
std::int64_t Models::mission_ = 0;
std::int64_t Models::second_ = 0;
std::int64_t Models::foreign_ = 0;

TEST_F(Models, AFitIsStoredWithItsTrainingMissionsAndPredicts) {
  const auto f = app::fit_model(ctx_, "sim-a", {mission_, second_}, options());
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_GT(f->stored.id, 0);
  EXPECT_EQ(f->stored.training_missions, (std::vector<std::int64_t>{mission_, second_}));
  EXPECT_EQ(f->stored.vehicle_id, "sim-a");
  const auto listed = app::list_models(ctx_, std::string("sim-a"));
  ASSERT_FALSE(listed.empty());
  EXPECT_EQ(listed.back().id, f->stored.id);
  EXPECT_TRUE(app::list_models(ctx_, std::string("sim-b")).empty());
  EXPECT_EQ(app::get_model(ctx_, f->stored.id)->vehicle_id, "sim-a");
  EXPECT_EQ(app::model_or_latest(ctx_, std::nullopt, "sim-a")->id, listed.back().id);
  // The model predicts a right turn that ends right of the start.
  app::PredictQuery q;
  q.vehicle_id = "sim-a";
  q.speed_mps = 1.0;
  q.dheading_deg = 90.0;
  q.method = app::PredictionMethod::model;
  const auto p = app::predict(ctx_, q);
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->model_id, listed.back().id);
  EXPECT_GT(p->trajectory.back().x_m, 1.0);
}

TEST_F(Models, MissionsOfAnotherVehicleOrNoneAreRefusedNamingMissions) {
  for (const auto& missions : {std::vector<std::int64_t>{}, std::vector<std::int64_t>{foreign_},
                               std::vector<std::int64_t>{mission_, 9999}}) {
    const auto f = app::fit_model(ctx_, "sim-a", missions, options());
    ASSERT_FALSE(f);
    EXPECT_EQ(f.error().code, app::ErrorCode::invalid_argument);
    EXPECT_EQ(f.error().field, "missions");
  }
  EXPECT_EQ(app::sweep_model_history(ctx_, "sim-a", {foreign_}, options()).error().field,
            "missions");
  EXPECT_EQ(app::get_model(ctx_, 9999).error().code, app::ErrorCode::not_found);
  EXPECT_EQ(app::model_or_latest(ctx_, std::nullopt, "nobody").error().code,
            app::ErrorCode::not_found);
}

TEST_F(Models, TheSweepHasOneRowPerHistoryLength) {
  const auto rows = app::sweep_model_history(ctx_, "sim-a", {mission_, second_}, {});
  ASSERT_TRUE(rows) << rows.error().message;
  ASSERT_EQ(rows->size(), 10u);
  for (std::size_t i = 0; i < rows->size(); ++i) {
    EXPECT_DOUBLE_EQ((*rows)[i].history_s, 2.0 * static_cast<double>(i + 1));
    EXPECT_TRUE(std::isfinite((*rows)[i].train_one_step_rms_deg));
  }
}

TEST_F(Models, HeadingsShowTheModelBesideTheMeasurement) {
  const auto f = app::fit_model(ctx_, "sim-a", {mission_}, options());
  ASSERT_TRUE(f) << f.error().message;
  const auto h = app::model_headings(ctx_, f->stored.id, second_, 500);
  ASSERT_TRUE(h) << h.error().message;
  EXPECT_EQ(h->model_id, f->stored.id);
  EXPECT_EQ(h->mission_id, second_);
  std::size_t samples = 0, predicted = 0;
  for (const auto& s : h->segments) {
    EXPECT_EQ(s.heading_deg.size(), s.one_step_deg.size());
    samples += s.heading_deg.size();
    for (const auto& v : s.one_step_deg)
      predicted += v.has_value();
  }
  EXPECT_EQ(samples, 500u);
  EXPECT_GT(predicted, 400u);
  EXPECT_EQ(app::model_headings(ctx_, 9999, second_, 10).error().code, app::ErrorCode::not_found);
  EXPECT_EQ(app::model_headings(ctx_, f->stored.id, 9999, 10).error().code,
            app::ErrorCode::not_found);
}

TEST_F(Models, TheComparisonScoresEveryCellAndUsesAModelOnlyWhenThereIsOne) {
  app::CompareQuery q;
  q.vehicle_id = "sim-b";
  const auto without = app::compare(ctx_, q);  // sim-b has no model
  ASSERT_TRUE(without) << without.error().message;
  EXPECT_FALSE(without->model);
  EXPECT_EQ(without->cells.size(), 4u);
  for (const auto& c : without->cells) {
    EXPECT_FALSE(c.model);
    EXPECT_GE(c.instantaneous.mse_m2, 0.0);
  }
  q.vehicle_id = "sim-a";
  const auto f = app::fit_model(ctx_, "sim-a", {mission_}, options());
  ASSERT_TRUE(f);
  q.model_id = f->stored.id;
  const auto with = app::compare(ctx_, q);
  ASSERT_TRUE(with) << with.error().message;
  ASSERT_TRUE(with->model);
  EXPECT_EQ(with->model->id, f->stored.id);
  for (const auto& c : with->cells)
    EXPECT_TRUE(c.model) << c.speed_mps << " " << c.dheading_deg;
  q.without_model = true;
  EXPECT_FALSE(app::compare(ctx_, q)->model);
  q.vehicle_id = "nobody";
  EXPECT_EQ(app::compare(ctx_, q).error().code, app::ErrorCode::not_found);
  q.vehicle_id = "sim-a";
  q.without_model = false;
  q.model_id = 9999;
  EXPECT_EQ(app::compare(ctx_, q).error().code, app::ErrorCode::not_found);
}

}  // namespace
