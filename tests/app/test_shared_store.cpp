// Several stations on one PostgreSQL database: a table one station's turns change is seen by
// another, whose cache learns of the change from the database's notifications (not by asking
// the database on every prediction), and missions of other stations are left alone.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "app/ckt_tables.hpp"
#include "app/context.hpp"
#include "app/mission_liveness.hpp"
#include "app/station_identity.hpp"
#include "app/store_link.hpp"
#include "app/store_writer.hpp"
#include "app/table_cache.hpp"
#include "store/postgresql.hpp"
#include "store/spool.hpp"
#include "store/sqlite.hpp"
#include "store/store.hpp"
#include "support/pg_cluster.hpp"
#include "support/polling.hpp"
#include "support/synthetic_turns.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace avk;

std::int64_t add_turns(store::Store& s, double speed_mps, int n) {
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
  const auto m = s.missions().create("usim-1", "collection", "{}");
  for (int k = 0; k < n; ++k) {
    avk::testing::ArcTurnSpec spec;
    spec.speed_mps = speed_mps;
    spec.dheading_deg = 45.0 * (1 + k % 2);
    spec.seed = static_cast<unsigned>(k + 1);
    spec.vehicle_id = "usim-1";
    s.turns().add(m, avk::testing::make_arc_turn(spec), kinematics::TurnStatus::ok, "");
  }
  return m;
}

std::size_t turns_in(const app::VehicleTable& t) {
  std::size_t n = 0;
  for (const auto& c : t.table->cells())
    n += c.n_turns;
  return n;
}

TEST(SharedStore, ANotificationIsWhatRefreshesAFollowingCache) {
  avk::testing::PgTestDb pg;
  store::Store other(pg.conninfo());
  add_turns(other, 1.0, 4);
  app::Context station(pg.conninfo());
  // An hour between checks: only a notification can make this cache read the store again.
  app::TableCache cache(std::chrono::hours(1));
  store::TableChangeListener listener(pg.conninfo());
  cache.follow_changes();
  auto first = cache.get(station, "usim-1");
  ASSERT_TRUE(first.ok());
  EXPECT_EQ(turns_in(first.value()), 4u);

  add_turns(other, 1.5, 2);
  // Unannounced, the cache answers from what it built.
  EXPECT_EQ(turns_in(cache.get(station, "usim-1").value()), 4u);
  ASSERT_TRUE(avk::testing::within(std::chrono::seconds(60), [&] {
    for (const auto& vehicle : listener.wait(100))
      if (vehicle == "usim-1") return true;
    return false;
  }));
  // Another vehicle's change leaves this vehicle's table as built; its own is read again.
  cache.changed("usim-2");
  EXPECT_EQ(turns_in(cache.get(station, "usim-1").value()), 4u);
  cache.changed("usim-1");
  EXPECT_EQ(turns_in(cache.get(station, "usim-1").value()), 6u);
}

TEST(SharedStore, AStartedStationSeesTheTurnsAnotherStationStores) {
  avk::testing::PgTestDb pg;
  store::Store other(pg.conninfo());
  add_turns(other, 1.0, 3);
  app::Context station(pg.conninfo());
  station.start();
  ASSERT_EQ(turns_in(station.tables().get(station, "usim-1").value()), 3u);
  add_turns(other, 1.5, 3);
  EXPECT_TRUE(avk::testing::within(std::chrono::seconds(60), [&] {
    return turns_in(station.tables().get(station, "usim-1").value()) == 6u;
  }));
  station.shutdown();
}

TEST(SharedStore, AnotherStationsRunningMissionIsNotTakenForAnOrphan) {
  avk::testing::PgTestDb pg;
  store::Store elsewhere(pg.conninfo());
  elsewhere.set_station_id("station-elsewhere");
  elsewhere.vehicles().upsert({"usim-2", "usim", 2.0, 1.2});
  const auto theirs = elsewhere.missions().create("usim-2", "theirs", "{}");
  elsewhere.missions().set_status(theirs, store::MissionStatus::running, "", 0.0);
  // A pid that is not alive here: on its own station that would make the mission an orphan.
  elsewhere.missions().set_runner(theirs, 999999999);
  ASSERT_NE(app::station_id(), "station-elsewhere");
  store::Store here(pg.conninfo());
  EXPECT_EQ(app::mark_orphaned_missions_interrupted(here), 0);
  EXPECT_EQ(here.missions().get(theirs)->status, store::MissionStatus::running);
  EXPECT_EQ(here.missions().get(theirs)->station_id, "station-elsewhere");
}

}  // namespace

namespace {

TEST(SharedStore, AClassTablePoolsTheTurnsOfEveryVehicleOfTheKindOnRequest) {
  avk::testing::PgTestDb pg;
  store::Store s(pg.conninfo());
  const auto add = [&](const std::string& id, const std::string& kind, double speed, int n) {
    s.vehicles().upsert({id, kind, 2.0, 1.2});
    const auto m = s.missions().create(id, "collection", "{}");
    for (int k = 0; k < n; ++k) {
      avk::testing::ArcTurnSpec spec;
      spec.speed_mps = speed;
      spec.dheading_deg = 90.0;
      spec.seed = static_cast<unsigned>(k + 1);
      spec.vehicle_id = id;
      s.turns().add(m, avk::testing::make_arc_turn(spec), kinematics::TurnStatus::ok, "");
    }
  };
  add("m200-a", "catamaran:m200", 1.0, 3);
  add("m200-b", "catamaran:m200", 1.5, 2);
  add("usim-1", "usim", 1.0, 4);
  app::Context station(pg.conninfo());
  const auto own = app::vehicle_table(station, "m200-a");
  ASSERT_TRUE(own.ok());
  EXPECT_EQ(turns_in(own.value()), 3u);
  EXPECT_TRUE(own.value().pooled_vehicles.empty());
  const auto pooled = app::class_table(station, "m200-a");
  ASSERT_TRUE(pooled.ok());
  EXPECT_EQ(turns_in(pooled.value()), 5u);
  EXPECT_EQ(pooled.value().pooled_vehicles, (std::vector<std::string>{"m200-a", "m200-b"}));
  EXPECT_EQ(pooled.value().table->grid().speeds_mps, (std::vector<double>{1.0, 1.5}));
  EXPECT_FALSE(app::class_table(station, "nobody").ok());
}

}  // namespace

namespace {

// The station dies after storing the spooled writes but before removing them from the spool: the
// next replay finds every one stored already and stores nothing twice.
TEST(SharedStore, ASpoolReplayedAgainStoresNothingTwice) {
  avk::testing::TempDir dir("avk_spool_again");
  avk::testing::PgCluster pg(dir.path() / "cluster");
  const std::string db = pg.conninfo(pg.create_database());
  const std::string spool = (dir.path() / "spool.db").string();
  app::set_spool_path(spool);
  store::Store s(db);
  s.vehicles().upsert({"usim-1", "usim", 2.0, 1.2});
  const auto m = s.missions().create("usim-1", "collection", "{}");
  std::vector<store::NavRow> first, second;
  for (int i = 0; i < 20; ++i)
    (i < 10 ? first : second).push_back({0.1 * i, 1.0 * i, 0.0, 90.0, 1.0, 90.0, 1.0, "turn"});
  avk::testing::ArcTurnSpec spec;
  spec.vehicle_id = "usim-1";
  const auto turn = avk::testing::make_arc_turn(spec);

  pg.stop();
  {
    app::StoreWriter w(s);
    w.nav(m, first);
    w.event(m, 1.0, "containment", "left the region");
    w.condition_set(m, {0.5, 1.5, 1.0, "set"});
    EXPECT_FALSE(w.turn(m, turn, kinematics::TurnStatus::ok, "", {}).has_value());
    w.nav(m, second);
    EXPECT_FALSE(w.replay(true));  // the server is still away
  }
  // What the spool held before the replay, as the dying station would leave it.
  const std::string before = (dir.path() / "before.db").string();
  store::Connection(spool).exec("VACUUM INTO '" + before + "'");
  pg.start();
  const auto counts = [&] {
    return std::vector<std::int64_t>{
        s.navigation().count(m), static_cast<std::int64_t>(s.missions().events(m).size()),
        static_cast<std::int64_t>(s.missions().condition_sets(m).size()),
        static_cast<std::int64_t>(s.turns().list({}).size())};
  };
  {
    app::StoreWriter w(s);
    ASSERT_TRUE(w.replay(true));
  }
  EXPECT_EQ(counts(), (std::vector<std::int64_t>{20, 1, 1, 1}));
  for (const char* suffix : {"", "-wal", "-shm"})
    std::filesystem::remove(spool + suffix);
  std::filesystem::copy_file(before, spool);
  {
    app::StoreWriter w(s);
    ASSERT_TRUE(w.replay(true));
  }
  EXPECT_EQ(counts(), (std::vector<std::int64_t>{20, 1, 1, 1}));
  EXPECT_EQ(store::Spool(spool).count(), 0);
}

}  // namespace
