// Two stations on one PostgreSQL database: two real `avk serve` processes, each flying a mission
// on its own simulated vehicle at the same time, each answering for the other's vehicle from the
// turns the other stored (its table cache told of them by the database), and their missions
// kept apart by the ids the database gives.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <map>
#include <set>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "store/postgresql.hpp"
#include "support/http_client.hpp"
#include "support/pg_cluster.hpp"
#include "support/polling.hpp"
#include "support/spawn_avk.hpp"
#include "support/station_requests.hpp"
#include "support/temp_dir.hpp"

namespace {

using avk::testing::http_call;
using nlohmann::json;

constexpr const char* kToken = "shared-token-Rz8qW3nLx5VtK9mPc2Jd7HbF4sGy";

json get_json(unsigned short port, const std::string& target) {
  return json::parse(http_call(port, "GET", target).body);
}

std::size_t turns_in_table(unsigned short port, const std::string& vehicle) {
  const auto r = http_call(port, "GET", "/api/v1/vehicles/" + vehicle + "/ckt");
  if (r.status != 200) return 0;
  std::size_t n = 0;
  const json table = json::parse(r.body);
  for (const auto& c : table["cells"])
    n += c["n_turns"].get<std::size_t>();
  return n;
}

struct Station {
  avk::testing::ServeProcess process;
  std::string vehicle;
  ~Station() {
    if (process.pid > 0) {
      ::kill(process.pid, SIGTERM);
      ::waitpid(process.pid, nullptr, 0);
    }
  }
};

TEST(SharedStations, TwoServersOnOneDatabaseEachFlyAMissionAndSeeTheOthersTable) {
  avk::testing::PgTestDb pg;
  avk::testing::TempDir dir("avk_shared_stations");
  auto serve = [&](const std::string& name, const std::string& vehicle) {
    const std::string d = (dir.path() / name).string();
    return avk::testing::spawn_serve(
        {"--db", pg.url(), "--sim", "--vehicle-id", vehicle, "--station-id", name, "--port", "0",
         "--realtime-factor", "100", "--token", kToken, "--spool", d + ".spool.db", "--token-file",
         d + ".token"},
        d + ".log");
  };
  Station a{serve("station-a", "alpha"), "alpha"};
  Station b{serve("station-b", "bravo"), "bravo"};
  ASSERT_NE(a.process.port, 0);
  ASSERT_NE(b.process.port, 0);

  std::set<std::string> missions;
  for (const Station* s : {&a, &b}) {
    const auto created =
        http_call(s->process.port, "POST", "/api/v1/vehicles/" + s->vehicle + "/missions",
                  avk::testing::small_mission("shared"), avk::testing::control_headers(kToken));
    ASSERT_EQ(created.status, 201) << created.body;
    missions.insert(created.headers.at("Location"));
  }
  // The database gave the two missions different ids.
  ASSERT_EQ(missions.size(), 2u);
  for (const std::string& m : missions)
    ASSERT_TRUE(avk::testing::within(std::chrono::seconds(180), [&] {
      for (const Station* s : {&a, &b}) {
        const auto r = http_call(s->process.port, "GET", m);
        if (r.status == 200 && json::parse(r.body)["status"] == "done") return true;
      }
      return false;
    })) << m;

  // Each station answers for its own vehicle and for the other's, from the same turns.
  for (const Station* here : {&a, &b})
    for (const Station* vehicle : {&a, &b})
      EXPECT_TRUE(avk::testing::within(
          std::chrono::seconds(30),
          [&] { return turns_in_table(here->process.port, vehicle->vehicle) == 4u; }))
          << "station on " << here->vehicle << " asked for " << vehicle->vehicle;
  // Both see both missions, each recorded with the station that ran it.
  for (const Station* s : {&a, &b})
    EXPECT_EQ(get_json(s->process.port, "/api/v1/missions").size(), 2u);
  avk::store::PgConnection check(pg.conninfo());
  auto q = check.prepare("SELECT count(DISTINCT station_id) FROM missions");
  ASSERT_TRUE(q.step());
  EXPECT_EQ(q.column_int64(0), 2);
}

}  // namespace
