// A primary with a streaming-replication standby (two clusters on loopback, docs/postgresql.md):
// the primary is killed during a mission, the standby promoted, and the station, given a
// connection string that lists both with target_session_attrs=read-write, finds the new primary
// and finishes the mission there: every finished turn is in the promoted standby once. The
// primary waits for the standby at every commit (synchronous_standby_names): a turn the station
// counted as stored is on the standby too.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include "store/postgresql.hpp"
#include "support/mission_run_exit.hpp"
#include "support/pg_cluster.hpp"
#include "support/polling.hpp"
#include "support/spawn_avk.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace avk;

TEST(PgStandby, APromotedStandbyTakesOverAMissionAndHoldsEveryFinishedTurnOnce) {
  avk::testing::TempDir dir("avk_pg_standby");
  avk::testing::PgCluster primary(dir.path() / "primary");
  const std::string name = primary.create_database();
  avk::testing::PgCluster standby(dir.path() / "standby",
                                  avk::testing::PgCluster::StandbyOf{primary});
  {
    store::PgConnection admin(primary.conninfo());
    admin.exec("ALTER SYSTEM SET synchronous_standby_names = '*'");
    admin.exec("SELECT pg_reload_conf()");
  }
  // The standby streams: the primary lists it as a synchronous sender.
  ASSERT_TRUE(avk::testing::within(std::chrono::seconds(60), [&] {
    return avk::testing::pg_number(
               primary.conninfo(),
               "SELECT count(*) FROM pg_stat_replication WHERE sync_state = 'sync'") == 1;
  })) << avk::testing::file_text(standby.log("server"));

  const std::string both = "host=" + primary.dir().string() + "," + standby.dir().string() +
                           " port=" + std::to_string(primary.port()) + "," +
                           std::to_string(standby.port()) + " user=avk dbname=" + name +
                           " connect_timeout=5 target_session_attrs=read-write";
  const std::string log = (dir.path() / "mission.log").string();
  const pid_t child = avk::testing::spawn_avk(
      {"mission", "run", "--config", std::string(AVK_SOURCE_DIR) + "/examples/thesis-fig4-1.json",
       "--db", both, "--sim", "--vehicle", "usim", "--realtime", "--realtime-factor", "20",
       "--station-id", "standby-test", "--spool", (dir.path() / "spool.db").string()},
      log);
  ASSERT_GT(child, 0);
  const std::string turns = "SELECT count(*) FROM turns";
  ASSERT_TRUE(avk::testing::within(std::chrono::seconds(240), [&] {
    return avk::testing::pg_number(primary.conninfo(name), turns) >= 3;
  })) << avk::testing::file_text(log);
  primary.kill9();
  standby.promote();
  const auto run = avk::testing::finished_mission_run(child, log);
  ASSERT_TRUE(run.exited_0) << run.output;
  const std::int64_t finished = run.turns_finished;
  const std::string db = standby.conninfo(name);
  EXPECT_EQ(avk::testing::pg_number(db, turns), finished);
  EXPECT_EQ(avk::testing::pg_number(db, "SELECT count(DISTINCT record_key) FROM turns"), finished);
  EXPECT_EQ(avk::testing::pg_number(db, "SELECT count(*) FROM turns WHERE status = 'ok'"), 18);
  EXPECT_EQ(avk::testing::pg_number(db, "SELECT count(*) FROM missions WHERE status = 'done'"), 1);
}

}  // namespace
