// The vehicle's CKT as the station keeps it: built from its turns and rebuilt when new ones
// arrive, a cell, the export, and an import that stores nothing when the file is wrong.
#include <gtest/gtest.h>

#include <chrono>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "kinematics/ckt_file.hpp"
#include "support/stored_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using namespace avk;

class CktTables : public ::testing::Test {
 protected:
  avk::testing::TempDb db_{"avk_app_ckt"};
  app::Context ctx_{db_.path()};
};

TEST_F(CktTables, TheTableHoldsTheVehiclesCellsAndIsRebuiltForNewTurns) {
  const auto mission = avk::testing::store_arc_turns(ctx_.db(), "alpha", 1.0, 2);
  app::TableCache cache(std::chrono::milliseconds(0));  // re-checks on every call
  const auto first = cache.get(ctx_, "alpha");
  ASSERT_TRUE(first) << first.error().message;
  EXPECT_EQ(first->source, app::TableSource::turns);
  EXPECT_EQ(first->table->vehicle_id, "alpha");
  ASSERT_TRUE(first->fine);
  std::size_t turns = 0;
  for (const auto& c : first->table->cells())
    turns += c.n_turns;
  EXPECT_EQ(turns, 18u);  // 3 speeds x 3 heading changes x 2
  // Unchanged store: the same table object.
  EXPECT_EQ(cache.get(ctx_, "alpha")->table, first->table);
  avk::testing::ArcTurnSpec s;
  s.speed_mps = 1.0;
  s.dheading_deg = 40.0;
  s.lead_in_m = 1.5;
  s.radius_m = 3.0;
  s.vehicle_id = "alpha";
  ctx_.db().store_turn(mission, avk::testing::make_arc_turn(s), kinematics::TurnStatus::ok, "");
  const auto second = cache.get(ctx_, "alpha");
  ASSERT_TRUE(second);
  EXPECT_NE(second->table, first->table);
  turns = 0;
  for (const auto& c : second->table->cells())
    turns += c.n_turns;
  EXPECT_EQ(turns, 19u);
}

TEST_F(CktTables, ACellIsFoundOnTheGridOnly) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");
  const auto cell = app::ckt_cell(ctx_, "alpha", 1.0, 100.0);
  ASSERT_TRUE(cell) << cell.error().message;
  EXPECT_EQ(cell->cell.n_turns, 2u);
  // Lead-in 1.5 m, radius 3 m: advance 1.5 + 3 sin(100 deg), transfer 3 (1 - cos(100 deg)).
  EXPECT_NEAR(cell->cell.advance_m.mean, 1.5 + 3.0 * std::sin(100.0 * M_PI / 180.0), 0.05);
  EXPECT_NEAR(cell->cell.transfer_m.mean, 3.0 * (1.0 - std::cos(100.0 * M_PI / 180.0)), 0.05);
  EXPECT_EQ(cell->side, kinematics::TurnSide::right);
  EXPECT_DOUBLE_EQ(cell->dheading_deg, 100.0);
  // A port change: the same cell mirrored about the start heading (x -> -x), point for point.
  const auto port = app::ckt_cell(ctx_, "alpha", 1.0, -100.0);
  ASSERT_TRUE(port) << port.error().message;
  EXPECT_EQ(port->side, kinematics::TurnSide::left);
  EXPECT_DOUBLE_EQ(port->dheading_deg, -100.0);
  EXPECT_EQ(port->cell.n_turns, cell->cell.n_turns);
  ASSERT_EQ(port->trajectory.size(), cell->trajectory.size());
  for (std::size_t i = 0; i < cell->trajectory.size(); ++i) {
    EXPECT_DOUBLE_EQ(port->trajectory[i].x_m, -cell->trajectory[i].x_m);
    EXPECT_DOUBLE_EQ(port->trajectory[i].y_m, cell->trajectory[i].y_m);
  }
  ASSERT_EQ(port->turns.size(), 2u);
  ASSERT_TRUE(port->fit && cell->fit);
  EXPECT_DOUBLE_EQ(port->fit->back().x_m, -cell->fit->back().x_m);
  EXPECT_GT(cell->trajectory.back().x_m, 0.0);  // the table's turns are to starboard
  const auto off = app::ckt_cell(ctx_, "alpha", 1.1, 100.0);
  ASSERT_FALSE(off);
  EXPECT_EQ(off.error().code, app::ErrorCode::not_found);
  EXPECT_EQ(app::ckt_cell(ctx_, "nobody", 1.0, 100.0).error().code, app::ErrorCode::not_found);
}

TEST_F(CktTables, ExportNamesTheVehicleAndReadsBack) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");
  const auto t = app::ckt_for_export(ctx_, "alpha");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->vehicle_id, "alpha");
  const auto back = kinematics::parse_ckt_json(kinematics::ckt_to_json_string(*t));
  EXPECT_EQ(back.grid(), t->grid());
}

TEST_F(CktTables, AWrongFileIsRefusedAndNothingIsStored) {
  avk::testing::store_arc_turns(ctx_.db(), "alpha");
  kinematics::Ckt table = *app::ckt_for_export(ctx_, "alpha");
  const std::string file = kinematics::ckt_to_json_string(table);
  const auto wrong_vehicle = app::import_ckt(ctx_, "bravo", file);
  ASSERT_FALSE(wrong_vehicle);
  EXPECT_EQ(wrong_vehicle.error().code, app::ErrorCode::invalid_argument);
  EXPECT_EQ(wrong_vehicle.error().field, "vehicle_id");
  const auto truncated = app::import_ckt(ctx_, "alpha", file.substr(0, file.size() / 2));
  ASSERT_FALSE(truncated);
  EXPECT_NE(truncated.error().message.find("not a CKT file"), std::string::npos);
  EXPECT_FALSE(ctx_.db().latest_ckt_snapshot("alpha"));
  EXPECT_FALSE(ctx_.db().latest_ckt_snapshot("bravo"));
  const auto ok = app::import_ckt(ctx_, "alpha", file);
  ASSERT_TRUE(ok);
  EXPECT_EQ(ctx_.db().latest_ckt_snapshot("alpha")->id, ok->snapshot_id);
}

TEST_F(CktTables, BuildKeepsASnapshotOfTheMissionsItCameFrom) {
  const auto m = avk::testing::store_arc_turns(ctx_.db(), "alpha");
  avk::testing::store_arc_turns(ctx_.db(), "alpha", 3.0);  // a second mission, not asked for
  const auto built = app::build_ckt(ctx_, "alpha", {m}, {}, 0.9);
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_EQ(built->report.turns_used, 18u);
  EXPECT_EQ(built->table.vehicle_length_m, 0.9);
  EXPECT_FALSE(built->table.created_utc.empty());
  const auto snap = ctx_.db().latest_ckt_snapshot("alpha");
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->id, built->snapshot_id);
  EXPECT_EQ(snap->mission_ids, std::vector<std::int64_t>{m});
  EXPECT_EQ(app::build_ckt(ctx_, "alpha", {999}, {}).error().code, app::ErrorCode::not_found);
  EXPECT_EQ(app::build_ckt(ctx_, "nobody", {}, {}).error().code, app::ErrorCode::not_found);
}

}  // namespace
