// The vehicle's CKT as the station keeps it: built from its turns and rebuilt when new ones
// arrive, a cell, the export, and an import that stores nothing when the file is wrong.
#include <gtest/gtest.h>

#include <chrono>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/store_access.hpp"
#include "app/table_cache.hpp"
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
  const auto mission = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 1.0, 2);
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
  avk::testing::store_one_arc_turn(app::store_of(ctx_), mission, "alpha", 1.0, 40.0);
  const auto second = cache.get(ctx_, "alpha");
  ASSERT_TRUE(second);
  EXPECT_NE(second->table, first->table);
  turns = 0;
  for (const auto& c : second->table->cells())
    turns += c.n_turns;
  EXPECT_EQ(turns, 19u);
}

std::size_t turns_in(const kinematics::Ckt& table) {
  std::size_t n = 0;
  for (const auto& c : table.cells())
    n += c.n_turns;
  return n;
}

// A held-out prediction's table was rebuilt for every request: it is kept per vehicle and
// left-out set, and dropped when the vehicle's turns change, as the full table is.
TEST_F(CktTables, AHeldOutTableIsKeptPerLeftOutSetUntilTheTurnsChange) {
  const auto tight = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 1.0, 2);
  const auto wide = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 2.0, 1);
  app::TableCache cache(std::chrono::milliseconds(0));  // re-checks the store on every call
  store::TurnsLeftOut without_tight;
  without_tight.mission_id = tight;
  store::TurnsLeftOut without_wide;
  without_wide.mission_id = wide;
  const auto first = cache.held_out(ctx_, "alpha", false, without_tight);
  ASSERT_TRUE(first);
  EXPECT_EQ(turns_in(*first), 9u);  // the wide mission's: one a cell
  // Asked again with nothing stored since: the same table, not a new one.
  EXPECT_EQ(cache.held_out(ctx_, "alpha", false, without_tight), first);
  const auto other = cache.held_out(ctx_, "alpha", false, without_wide);
  ASSERT_TRUE(other);
  EXPECT_NE(other, first);
  EXPECT_EQ(turns_in(*other), 18u);
  EXPECT_EQ(cache.held_out(ctx_, "alpha", false, without_tight), first);
  // The same set of another vehicle's turns is not this one's.
  EXPECT_FALSE(cache.held_out(ctx_, "bravo", false, without_tight));

  avk::testing::store_one_arc_turn(app::store_of(ctx_), wide, "alpha", 1.0, 40.0);
  const auto after = cache.held_out(ctx_, "alpha", false, without_tight);
  ASSERT_TRUE(after);
  EXPECT_NE(after, first);
  EXPECT_EQ(turns_in(*after), 10u);
  EXPECT_EQ(cache.held_out(ctx_, "alpha", false, without_tight), after);
}

TEST_F(CktTables, HeldOutTablesAreBoundedAndTheLeastRecentlyUsedGoesFirst) {
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha", 1.0, 2);
  app::TableCache cache(std::chrono::hours(1));
  const auto turn_ids = app::store_of(ctx_).turns().list({});
  ASSERT_GT(turn_ids.size(), app::TableCache::kHeldOutTables + 1);
  const auto without = [&](std::size_t i) {
    store::TurnsLeftOut l;
    l.turn_id = turn_ids[i].id;
    return cache.held_out(ctx_, "alpha", false, l);
  };
  const auto kept = without(0);
  const auto one = without(1);
  ASSERT_TRUE(kept && one);
  // Turn 0's set is used again after each new one, so turn 1's is the least recently used when
  // the ninth set comes in.
  for (std::size_t i = 2; i <= app::TableCache::kHeldOutTables; ++i) {
    ASSERT_TRUE(without(i));
    EXPECT_EQ(without(0), kept);
  }
  EXPECT_EQ(without(0), kept);
  const auto again = without(1);
  ASSERT_TRUE(again);
  EXPECT_NE(again, one);
  EXPECT_EQ(turns_in(*again), turn_ids.size() - 1);
}

TEST_F(CktTables, ACellIsFoundOnTheGridOnly) {
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
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
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  const auto t = app::ckt_for_export(ctx_, "alpha");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->vehicle_id, "alpha");
  const auto back = kinematics::parse_ckt_json(kinematics::ckt_to_json_string(*t));
  EXPECT_EQ(back.grid(), t->grid());
}

TEST_F(CktTables, AWrongFileIsRefusedAndNothingIsStored) {
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  kinematics::Ckt table = *app::ckt_for_export(ctx_, "alpha");
  const std::string file = kinematics::ckt_to_json_string(table);
  const auto wrong_vehicle = app::import_ckt(ctx_, "bravo", file);
  ASSERT_FALSE(wrong_vehicle);
  EXPECT_EQ(wrong_vehicle.error().code, app::ErrorCode::invalid_argument);
  EXPECT_EQ(wrong_vehicle.error().field, "vehicle_id");
  const auto truncated = app::import_ckt(ctx_, "alpha", file.substr(0, file.size() / 2));
  ASSERT_FALSE(truncated);
  EXPECT_NE(truncated.error().message.find("not a CKT file"), std::string::npos);
  EXPECT_FALSE(app::store_of(ctx_).ckt_snapshots().latest("alpha"));
  EXPECT_FALSE(app::store_of(ctx_).ckt_snapshots().latest("bravo"));
  const auto ok = app::import_ckt(ctx_, "alpha", file);
  ASSERT_TRUE(ok);
  EXPECT_EQ(app::store_of(ctx_).ckt_snapshots().latest("alpha")->id, ok->snapshot_id);
}

TEST_F(CktTables, BuildKeepsASnapshotOfTheMissionsItCameFrom) {
  const auto m = avk::testing::store_arc_turns(app::store_of(ctx_), "alpha");
  avk::testing::store_arc_turns(app::store_of(ctx_), "alpha",
                                3.0);  // a second mission, not asked for
  const auto built = app::build_ckt(ctx_, "alpha", {m}, {}, 0.9);
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_EQ(built->report.turns_used, 18u);
  EXPECT_EQ(built->table.vehicle_length_m, 0.9);
  EXPECT_FALSE(built->table.created_utc.empty());
  const auto snap = app::store_of(ctx_).ckt_snapshots().latest("alpha");
  ASSERT_TRUE(snap);
  EXPECT_EQ(snap->id, built->snapshot_id);
  EXPECT_EQ(snap->mission_ids, std::vector<std::int64_t>{m});
  EXPECT_EQ(app::build_ckt(ctx_, "alpha", {999}, {}).error().code, app::ErrorCode::not_found);
  EXPECT_EQ(app::build_ckt(ctx_, "nobody", {}, {}).error().code, app::ErrorCode::not_found);
}

}  // namespace
