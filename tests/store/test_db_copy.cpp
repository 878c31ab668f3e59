// Copying a database between the engines: every table's rows, ids and bytes (doubles bit for bit)
// survive SQLite -> PostgreSQL -> SQLite; a copy never merges into a database that holds data; a
// copied PostgreSQL database hands out ids after the copied ones.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "kinematics/ckt.hpp"
#include "kinematics/water_frame.hpp"
#include "store/db_copy.hpp"
#include "store/store.hpp"
#include "support/pg_cluster.hpp"
#include "support/synthetic_turns.hpp"
#include "support/temp_db.hpp"

namespace {

using avk::kinematics::TurnSequence;
using avk::kinematics::TurnStatus;
using namespace avk::store;

TurnSequence arc(double dheading_deg, unsigned seed) {
  avk::testing::ArcTurnSpec spec;
  spec.dheading_deg = dheading_deg;
  spec.seed = seed;
  spec.position_noise_m = 0.05;
  spec.start = {3.0, 4.0, 20.0 * seed};
  spec.vehicle_id = "usim-1";
  return avk::testing::make_arc_turn(spec);
}

// A database holding a row of every table, with doubles that have no short decimal form.
void fill(Store& s) {
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
  s.vehicles().upsert({"m200", "catamaran", 1.0 / 3.0, std::nullopt});
  const auto m = s.missions().create("usim-1", "collection", R"({"speeds":[1.0]})");
  s.missions().set_status(m, MissionStatus::running, "", 0.1);
  std::vector<NavRow> nav;
  for (int i = 0; i < 50; ++i)
    nav.push_back({0.1 * i, std::sqrt(2.0) * i, -std::cbrt(3.0) * i, std::fmod(7.3 * i, 360.0),
                   1.0 / 7.0, i % 2 ? std::optional<double>(M_PI) : std::nullopt, 1.0, "turn"});
  s.navigation().append(m, nav);
  s.missions().append_event(m, 1.25, "containment", "left the region");
  s.missions().append_condition_set(m, {1.0 / 3.0, 2.0 / 3.0, 1.0, "set"});
  std::vector<std::pair<std::int64_t, TurnSequence>> water;
  for (unsigned k = 1; k <= 3; ++k) {
    const TurnSequence t = arc(30.0 * k, k);
    const auto id = s.turns().add(m, t, k == 2 ? TurnStatus::aborted : TurnStatus::ok,
                                  k == 2 ? "timeout" : "", {0.7, 1e-17, -2.5e-300});
    if (k != 2) water.push_back({id, avk::kinematics::in_water_frame(t, {0.1, -0.2}).normalized()});
  }
  StoredCurrent c;
  c.mission_id = m;
  c.t_s = 12.5;
  c.estimate.east_mps = 0.1;
  c.estimate.north_mps = -0.2;
  c.estimate.covariance = {1e-4, 2e-5, 3e-4};
  c.estimate.legs = 9;
  c.estimate.speed_scale = 1.02;
  c.estimate.residual_rms_mps = 0.01;
  s.currents().save(c, water);
  StoredModel model;
  model.vehicle_id = "usim-1";
  model.training_missions = {m};
  model.model.history = 2;
  model.model.error_coeffs = {0.1, -1.0 / 9.0};
  model.model.heading_coeffs = {1.5, -0.5};
  model.train_one_step_rms_deg = 1.25;
  s.models().save(model);
  avk::kinematics::Ckt table = avk::kinematics::Ckt::build(s.turns().load_normalized({}));
  table.vehicle_id = "usim-1";
  s.ckt_snapshots().save(table, {m});
  HarvestRecord h;
  h.mission_id = m;
  h.steps = 4;
  s.harvests().save(h);
  s.missions().set_status(m, MissionStatus::done, "finished", 99.5);
}

// Every row of every table as text, doubles by their bits, in key order.
std::vector<std::string> dump(Store& s) {
  std::vector<std::string> out;
  for (const char* table :
       {"vehicles", "missions", "nav_samples", "condition_sets", "mission_events", "turns",
        "harvests", "mission_currents", "yaw_models", "ckt_snapshots"}) {
    const std::string key = std::string(table) == "mission_currents" ? "mission_id"
                            : std::string(table) == "nav_samples"    ? "t_s"
                                                                     : "id";
    auto q = s.database().prepare(std::string("SELECT * FROM ") + table + " ORDER BY " + key);
    while (q.step()) {
      std::string row = table;
      for (int c = 0; c < q.column_count(); ++c) {
        const std::string name = q.column_name(c);
        if (name == "rowid") continue;  // PostgreSQL's column, SQLite's hidden one
        row.append(" ").append(name).append("=");
        switch (q.column_kind(c)) {
          case ColumnKind::null:
            row.append("NULL");
            break;
          case ColumnKind::integer:
            row.append(std::to_string(q.column_int64(c)));
            break;
          case ColumnKind::real:
            row.append("r").append(
                std::to_string(std::bit_cast<std::uint64_t>(q.column_double(c))));
            break;
          case ColumnKind::text:
            row.append("'").append(q.column_text(c)).append("'");
            break;
          case ColumnKind::blob:
            row.append("b");
            for (const unsigned char byte : q.column_blob(c))
              row.append(std::to_string(byte)).append(".");
            break;
        }
      }
      out.push_back(row);
    }
  }
  return out;
}

TEST(DbCopy, SqliteToPostgresqlToSqliteKeepsEveryRowBitForBit) {
  avk::testing::TempDb first, last;
  avk::testing::PgTestDb pg;
  std::vector<std::string> original;
  {
    Store s(first.path());
    fill(s);
    original = dump(s);
  }
  ASSERT_GT(original.size(), 60u);
  {
    Store from(first.path()), to(pg.conninfo());
    const auto counts = copy_database(from, to);
    ASSERT_EQ(counts.size(), 10u);
    EXPECT_EQ(counts[2].table, "nav_samples");
    EXPECT_EQ(counts[2].rows, 50);
    EXPECT_EQ(dump(to), original);
  }
  {
    Store from(pg.conninfo()), to(last.path());
    copy_database(from, to);
    EXPECT_EQ(dump(to), original);
    EXPECT_TRUE(to.integrity_check());
  }
  // The reads the station makes agree too: the CKT's turns, in the water frame where known.
  Store a(first.path()), b(pg.conninfo()), c(last.path());
  const auto turns =
      a.turns().load_normalized({}, "usim-1", false, TurnFrameChoice::water_where_known);
  EXPECT_EQ(b.turns().load_normalized({}, "usim-1", false, TurnFrameChoice::water_where_known),
            turns);
  EXPECT_EQ(c.turns().load_normalized({}, "usim-1", false, TurnFrameChoice::water_where_known),
            turns);
  // New rows in the copied PostgreSQL database take ids after the copied ones.
  const auto newest = b.missions().list().back().id;
  EXPECT_GT(b.missions().create("usim-1", "after", "{}"), newest);
}

TEST(DbCopy, ATargetWithDataIsRefusedAndKeepsWhatItHeld) {
  avk::testing::TempDb source;
  avk::testing::PgTestDb pg;
  {
    Store s(source.path());
    fill(s);
  }
  Store from(source.path()), to(pg.conninfo());
  to.vehicles().upsert({"other", "usim", 2.0, 1.0});
  const auto mine = to.missions().create("other", "kept", "{}");
  try {
    copy_database(from, to);
    FAIL() << "a copy merged into a database holding data";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("empty database"), std::string::npos) << e.what();
  }
  ASSERT_EQ(to.missions().list().size(), 1u);
  EXPECT_EQ(to.missions().list()[0].id, mine);
  EXPECT_TRUE(to.turns().list({}).empty());
}

}  // namespace
