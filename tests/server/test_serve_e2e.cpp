// The ground station end to end: a real server on an ephemeral loopback port, a mission started
// over REST and followed over a real WebSocket, and a kill -9 of a real `avk serve` process.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <chrono>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"
#include "store/store.hpp"
#include "support/http_client.hpp"
#include "support/sim_station.hpp"
#include "support/spawn_avk.hpp"
#include "support/station_requests.hpp"
#include "support/temp_db.hpp"
#include "support/ws_client.hpp"

namespace {

using avk::testing::http_call;
using avk::testing::WsClient;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Random-looking: `avk serve --token` refuses runs such as 0123456789 (server/token_strength.hpp).
constexpr const char* kToken = "e2e-token-Kq7vX2mPz9LwT4bN8cRj5YhD3sFg";

TEST(ServeE2E, MissionOverRestFollowedOverTheStreamAndEveryTurnIsServed) {
  avk::testing::TempDb db("avk_e2e");
  avk::server::StreamHub hub;
  avk::server::Station station(avk::testing::sim_station_options(db.path(), kToken, 100.0), hub);
  station.start();
  avk::server::HttpServer server({}, station, hub);
  server.start();
  const unsigned short port = server.port();

  WsClient ws(port);
  const json hello = json::parse(*ws.read_text(std::chrono::seconds(5)));
  EXPECT_EQ(hello["type"], "hello");
  EXPECT_EQ(hello["session_id"], hub.session_id());
  ws.send(R"({"subscribe":["turn","mission","nav"]})");

  const auto created =
      http_call(port, "POST", "/api/v1/vehicles/sim-usim/missions",
                avk::testing::small_mission("e2e"), avk::testing::control_headers(kToken));
  ASSERT_EQ(created.status, 201) << created.body;
  EXPECT_EQ(created.headers.at("Location"), "/api/v1/missions/1");

  std::set<std::int64_t> finished;
  std::map<std::string, std::uint64_t> last_seq;
  std::size_t nav = 0;
  std::string state;
  std::optional<json> started;  // the turn under way, as the stream announced it
  std::set<double> sides_seen;
  const auto deadline = Clock::now() + std::chrono::seconds(90);
  while (state != "done" && Clock::now() < deadline) {
    const auto text = ws.read_text(std::chrono::seconds(10));
    ASSERT_TRUE(text.has_value()) << "the stream went quiet";
    const json m = json::parse(*text);
    if (!m.contains("topic")) continue;  // the subscription acknowledgement
    const std::string topic = m["topic"];
    const auto seq = m["seq"].get<std::uint64_t>();
    EXPECT_GT(seq, last_seq[topic]) << topic;
    last_seq[topic] = seq;
    if (topic == "nav") ++nav;
    if (topic == "turn" && m["data"]["event"] == "started") {
      started = m["data"];
      EXPECT_DOUBLE_EQ((*started)["t_s"].get<double>(), m["t"].get<double>());
      for (const char* k : {"x_m", "y_m", "heading_deg", "goal_heading_deg"})
        EXPECT_TRUE((*started)[k].is_number()) << k;
    } else if (topic == "turn") {
      // The side announced at the start is the side the turn was recorded with.
      ASSERT_TRUE(started.has_value()) << "a turn ended that never started: " << m.dump();
      EXPECT_DOUBLE_EQ((*started)["dheading_deg"].get<double>(),
                       m["data"]["goal_dheading_deg"].get<double>());
      sides_seen.insert((*started)["dheading_deg"].get<double>() < 0 ? -1.0 : 1.0);
      started.reset();
    }
    if (topic == "turn" && m["data"]["event"] == "finished")
      finished.insert(m["data"]["id"].get<std::int64_t>());
    if (topic == "mission") state = m["data"]["state"];
  }
  ASSERT_EQ(state, "done");
  EXPECT_GT(nav, 10u);
  EXPECT_EQ(finished.size(), 4u);
  EXPECT_EQ(sides_seen, (std::set<double>{-1.0, 1.0}));  // turns to port and to starboard
  // Every finished turn the stream announced is in /turns and in the table.
  const json turns =
      json::parse(http_call(port, "GET", "/api/v1/turns?mission=1&status=ok&limit=100").body);
  std::set<std::int64_t> listed;
  for (const auto& t : turns["items"])
    listed.insert(t["id"].get<std::int64_t>());
  EXPECT_EQ(listed, finished);
  const json ckt = json::parse(http_call(port, "GET", "/api/v1/vehicles/sim-usim/ckt").body);
  std::size_t in_table = 0;
  for (const auto& c : ckt["cells"])
    in_table += c["n_turns"].get<std::size_t>();
  EXPECT_EQ(in_table, finished.size());
  server.stop();
  station.shutdown();
}

// --- a real `avk serve`, killed ----------------------------------------------------------

using avk::testing::ServeProcess;

ServeProcess spawn_serve(const std::string& db, const std::string& log, bool with_token = true) {
  std::vector<std::string> args = {"--db", db, "--sim", "--port", "0", "--realtime-factor", "100"};
  if (with_token) {
    args.push_back("--token");
    args.push_back(kToken);
  }
  return avk::testing::spawn_serve(args, log);
}

json get_json(unsigned short port, const std::string& target) {
  return json::parse(http_call(port, "GET", target).body);
}

// `avk serve --sim` on db running mission 1 (`repeats` x 4 turns); port 0 when either failed.
ServeProcess serve_with_mission(const std::string& db, const std::string& log, int repeats) {
  ServeProcess p = spawn_serve(db, log);
  if (p.port &&
      http_call(p.port, "POST", "/api/v1/vehicles/sim-usim/missions",
                avk::testing::small_mission("e2e", repeats), avk::testing::control_headers(kToken))
              .status == 201)
    return p;
  if (p.pid > 0) {
    kill(p.pid, SIGKILL);
    waitpid(p.pid, nullptr, 0);
  }
  return {};
}

// Waits (60 s at most) until mission 1 has stored navigation; false when it never does.
bool wait_for_navigation(unsigned short port) {
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline) {
    if (!get_json(port, "/api/v1/missions/1/nav?limit=1")["items"].empty()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// The latest navigation time stored for a mission, read from the database file itself.
std::optional<double> last_nav_t_s(const std::string& db, std::int64_t mission_id) {
  avk::store::Store store(db);
  std::optional<double> last;
  std::int64_t after = 0;
  for (;;) {
    const auto page = store.navigation().page(mission_id, after, 10000);
    if (page.empty()) return last;
    for (const auto& row : page)
      last = std::max(last.value_or(row.row.t_s), row.row.t_s);
    after = page.back().rowid;
  }
}

TEST(ServeE2E, KillNineDuringAMissionLosesNoFinishedTurnAndTheMissionResumes) {
  avk::testing::TempDb db("avk_e2e_kill");
  const std::string log = db.path() + ".log";
  // Twelve turns: the kill comes after the second, and ten more leave seconds of wall time for
  // this thread to see the second one even on a loaded machine (at 100x a turn takes ~0.2 s).
  ServeProcess first = serve_with_mission(db.path(), log, 3);
  ASSERT_GT(first.port, 0) << "the server or its mission did not start";
  json before;
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline) {
    before = get_json(first.port, "/api/v1/turns?mission=1&status=ok");
    if (before["items"].size() >= 2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GE(before["items"].size(), 2u);
  ASSERT_EQ(kill(first.pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(first.pid, &status, 0), first.pid);

  // What the killed process left: its last navigation, and the latest time of anything stored.
  const auto nav_end_s = last_nav_t_s(db.path(), 1);
  ASSERT_TRUE(nav_end_s.has_value());
  const auto stored_end_s = avk::store::Store(db.path()).missions().clock_end_s(1);
  ASSERT_TRUE(stored_end_s.has_value());

  ServeProcess second = spawn_serve(db.path(), log);
  ASSERT_GT(second.port, 0);
  // The restart closes the mission as interrupted, ended where its record ends, so its elapsed
  // time is known (the banner showed "elapsed –"); when that was in wall-clock time is not.
  const json interrupted = get_json(second.port, "/api/v1/missions/1");
  EXPECT_EQ(interrupted["status"], "interrupted");
  ASSERT_TRUE(interrupted["ended_s"].is_number()) << interrupted.dump();
  EXPECT_DOUBLE_EQ(interrupted["ended_s"].get<double>(), *stored_end_s);
  EXPECT_GE(interrupted["ended_s"].get<double>(), *nav_end_s);
  EXPECT_GT(interrupted["ended_s"].get<double>(), interrupted["started_s"].get<double>());
  EXPECT_NE(interrupted["status_reason"].get<std::string>().find("stopped"), std::string::npos)
      << interrupted.dump();
  for (const auto& t : before["items"]) {
    const json again = get_json(second.port, "/api/v1/turns/" + t["id"].dump());
    EXPECT_EQ(again["advance_m"], t["advance_m"]);
  }
  ASSERT_EQ(http_call(second.port, "POST", "/api/v1/missions/1/resume", "",
                      avk::testing::control_headers(kToken))
                .status,
            200);
  json m;
  const auto done_by = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < done_by) {
    m = get_json(second.port, "/api/v1/missions/1");
    if (m["status"] == "done") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(m["status"], "done");
  EXPECT_GT(m["ended_s"].get<double>(), interrupted["ended_s"].get<double>());
  EXPECT_EQ(get_json(second.port, "/api/v1/turns?mission=1&status=ok")["items"].size(), 12u);
  // SIGTERM: a graceful stop.
  ASSERT_EQ(kill(second.pid, SIGTERM), 0);
  ASSERT_EQ(waitpid(second.pid, &status, 0), second.pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  std::filesystem::remove(log);
  std::filesystem::remove(db.path() + ".token");
}

// `docker stop` sends SIGTERM: the mission it interrupts is stored with its end (station clock and
// wall clock) and the reason, so after a restart its elapsed time is known.
TEST(ServeE2E, SigtermEndsARunningMissionAsInterruptedWithItsEndStored) {
  avk::testing::TempDb db("avk_e2e_term");
  const std::string log = db.path() + ".log";
  ServeProcess p = serve_with_mission(db.path(), log, 3);
  ASSERT_GT(p.port, 0) << "the server or its mission did not start";
  ASSERT_TRUE(wait_for_navigation(p.port));
  ASSERT_EQ(get_json(p.port, "/api/v1/missions/1")["status"], "running");
  ASSERT_EQ(kill(p.pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(p.pid, &status, 0), p.pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);

  const auto nav_end_s = last_nav_t_s(db.path(), 1);
  ASSERT_TRUE(nav_end_s.has_value());
  const auto m = avk::store::Store(db.path()).missions().get(1);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->status, avk::store::MissionStatus::interrupted);
  EXPECT_EQ(m->status_reason, "the server stopped");
  EXPECT_FALSE(m->runner_pid.has_value());
  ASSERT_TRUE(m->started_s.has_value());
  ASSERT_TRUE(m->ended_s.has_value()) << "no end stored: the banner shows elapsed \u2013";
  EXPECT_GE(*m->ended_s, *nav_end_s);
  EXPECT_GT(*m->ended_s, *m->started_s);
  ASSERT_TRUE(m->started_utc.has_value());
  ASSERT_TRUE(m->ended_utc.has_value());
  EXPECT_GE(*m->ended_utc, *m->started_utc);  // ISO 8601 orders as text

  // A restart leaves it as it was: the end the stop stored is not replaced.
  ServeProcess again = spawn_serve(db.path(), log);
  ASSERT_GT(again.port, 0);
  const json listed = get_json(again.port, "/api/v1/missions");
  ASSERT_EQ(listed.size(), 1u) << listed.dump();
  EXPECT_EQ(listed[0]["status"], "interrupted");
  ASSERT_TRUE(listed[0]["ended_s"].is_number()) << listed.dump();
  EXPECT_DOUBLE_EQ(listed[0]["ended_s"].get<double>(), *m->ended_s);
  EXPECT_EQ(listed[0]["ended_utc"], *m->ended_utc);
  ASSERT_EQ(kill(again.pid, SIGTERM), 0);
  ASSERT_EQ(waitpid(again.pid, &status, 0), again.pid);
  std::filesystem::remove(log);
  std::filesystem::remove(db.path() + ".token");
}

TEST(ServeE2E, FirstStartWritesAPrivateTokenAndPrintsTheDashboardUrl) {
  avk::testing::TempDb db("avk_e2e_token");
  const std::string log = db.path() + ".log";
  const std::string token_file = db.path() + ".token";
  std::filesystem::remove(token_file);
  ServeProcess p = spawn_serve(db.path(), log, false);
  ASSERT_GT(p.port, 0);
  struct stat st {};
  ASSERT_EQ(::stat(token_file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  std::string token;
  std::getline(std::ifstream(token_file), token);
  EXPECT_GE(token.size(), 16u);
  std::stringstream printed;
  printed << std::ifstream(log).rdbuf();
  EXPECT_NE(printed.str().find("?token=" + token), std::string::npos) << printed.str();
  // Control needs it; reads on loopback do not.
  EXPECT_EQ(http_call(p.port, "POST", "/api/v1/vehicles/sim-usim/missions",
                      avk::testing::small_mission("e2e"), {{"Content-Type", "application/json"}})
                .status,
            401);
  EXPECT_EQ(http_call(p.port, "POST", "/api/v1/vehicles/sim-usim/missions",
                      avk::testing::small_mission("e2e"),
                      {{"Content-Type", "application/json"}, {"Authorization", "Bearer " + token}})
                .status,
            201);
  EXPECT_EQ(http_call(p.port, "GET", "/api/v1/missions").status, 200);
  ASSERT_EQ(kill(p.pid, SIGTERM), 0);
  int status = 0;
  waitpid(p.pid, &status, 0);
  // The mission it was running is stored as interrupted, not lost.
  EXPECT_TRUE(WIFEXITED(status));
  std::filesystem::remove(log);
  std::filesystem::remove(token_file);
}

}  // namespace
