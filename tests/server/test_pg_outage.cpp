// A PostgreSQL server that goes away during a mission: killed (SIGKILL, as a crash) three times
// while `avk mission run` flies Figure 4-1 in real time x20, and started again each time. The
// mission goes on, its writes wait in the spool, and when the server is back they are replayed:
// every turn the mission finished is in the database exactly once, the spool is a sound SQLite
// file left empty.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include "store/postgresql.hpp"
#include "store/spool.hpp"
#include "store/sqlite.hpp"
#include "support/mission_run_exit.hpp"
#include "support/pg_cluster.hpp"
#include "support/polling.hpp"
#include "support/spawn_avk.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace avk;

std::int64_t spooled_turns(const std::string& spool) {
  try {
    store::Connection c(spool);
    auto s = c.prepare("SELECT count(*) FROM spooled_writes WHERE kind = 'turn'");
    return s.step() ? s.column_int64(0) : 0;
  } catch (const store::StoreError&) {
    return 0;  // not made yet
  }
}

TEST(PgOutage, KilledThreeTimesDuringAMissionEveryFinishedTurnIsStoredOnce) {
  avk::testing::TempDir dir("avk_pg_outage");
  avk::testing::PgCluster pg(dir.path() / "cluster");
  const std::string db = pg.conninfo(pg.create_database());
  const std::string spool = (dir.path() / "station.spool.db").string();
  const std::string log = (dir.path() / "mission.log").string();
  const pid_t child = avk::testing::spawn_avk(
      {"mission", "run", "--config", std::string(AVK_SOURCE_DIR) + "/examples/thesis-fig4-1.json",
       "--db", db, "--sim", "--vehicle", "usim", "--realtime", "--realtime-factor", "20",
       "--station-id", "outage-test", "--spool", spool},
      log);
  ASSERT_GT(child, 0);
  const std::string turns = "SELECT count(*) FROM turns";
  std::int64_t before = 0;
  for (int outage = 0; outage < 3; ++outage) {
    // The spool was replayed and a turn reached the database since: the server is in use when
    // it dies, and what the next outage spools is new.
    ASSERT_TRUE(avk::testing::within(
        std::chrono::seconds(240),
        [&] { return spooled_turns(spool) == 0 && avk::testing::pg_number(db, turns) > before; }))
        << "outage " << outage << "\n"
        << avk::testing::file_text(log);
    pg.kill9();
    // The mission goes on without it: a turn it finishes now waits in the spool.
    ASSERT_TRUE(
        avk::testing::within(std::chrono::seconds(240), [&] { return spooled_turns(spool) > 0; }))
        << "outage " << outage << "\n"
        << avk::testing::file_text(log);
    pg.start();
    ASSERT_TRUE(avk::testing::within(std::chrono::seconds(60),
                                     [&] { return avk::testing::pg_number(db, turns) >= 0; }));
    before = avk::testing::pg_number(db, turns);
  }
  const auto run = avk::testing::finished_mission_run(child, log);
  ASSERT_TRUE(run.exited_0) << run.output;
  const std::int64_t finished = run.turns_finished;
  // Every cell once at least (a turn given up and flown again is finished twice).
  EXPECT_GE(finished, 18) << run.output;
  EXPECT_EQ(avk::testing::pg_number(db, "SELECT count(*) FROM turns WHERE status = 'ok'"), 18);
  // Every finished turn once: as many rows as turns, each under its own key.
  EXPECT_EQ(avk::testing::pg_number(db, turns), finished);
  EXPECT_EQ(avk::testing::pg_number(db, "SELECT count(DISTINCT record_key) FROM turns"), finished);
  EXPECT_EQ(avk::testing::pg_number(
                db,
                "SELECT count(*) FROM missions WHERE status = 'done' AND runner_pid IS NULL "
                "AND station_id = 'outage-test'"),
            1);
  store::Spool left(spool);
  EXPECT_TRUE(left.integrity_check());
  EXPECT_EQ(left.count(), 0);
}

}  // namespace
