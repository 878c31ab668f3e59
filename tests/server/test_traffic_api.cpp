// AIS traffic in the station: `avk serve --ais` watches a real gpsd (gpsfake serving the
// simulated traffic's AIVDM) and GET /api/v1/traffic answers the contacts on the local grid, with
// their names; without a source it says it watches nothing; --ais needs a datum.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "sim/ais_traffic.hpp"
#include "support/cli_run.hpp"
#include "support/example_file.hpp"
#include "support/gpsfake.hpp"
#include "support/http_client.hpp"
#include "support/spawn_avk.hpp"
#include "support/temp_db.hpp"
#include "support/temp_dir.hpp"
#include "support/traffic_log.hpp"
#include "vehicle/local_grid.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string read_file(const std::string& path) {
  std::stringstream s;
  s << std::ifstream(path).rdbuf();
  return s.str();
}

// A served station, stopped (SIGTERM, then waited for) and its files removed however the test
// ends.
struct Served {
  avk::testing::ServeProcess p;
  std::string db, log;
  ~Served() {
    if (p.pid > 0) {
      ::kill(p.pid, SIGTERM);
      int status = 0;
      ::waitpid(p.pid, &status, 0);
    }
    std::error_code ec;
    fs::remove(log, ec);
    fs::remove(db + ".token", ec);
  }
  json traffic() const {
    const auto r = avk::testing::http_call(p.port, "GET", "/api/v1/traffic");
    EXPECT_EQ(r.status, 200) << r.body;
    return json::parse(r.body, nullptr, false);
  }
};

TEST(TrafficApi, ContactsFromGpsdAppearOnTheLocalGridWithTheirNames) {
  const auto traffic =
      avk::sim::AisTraffic::parse(avk::testing::example_text("traffic-charles.json"));
  const double t_s = 47.3;
  avk::testing::TempDir dir("traffic_api");
  dir.write("traffic.aivdm", avk::testing::traffic_log_at(traffic, t_s));
  avk::testing::Gpsfake gpsd(dir.path() / "traffic.aivdm");

  avk::testing::TempDb db("avk_traffic_api");
  const auto& datum = traffic.datum();
  const std::string datum_text =
      std::to_string(datum.lat_deg) + "," + std::to_string(datum.lon_deg);
  Served s{avk::testing::spawn_serve({"--db", db.path(), "--port", "0", "--datum", datum_text,
                                      "--ais", "127.0.0.1:" + gpsd.port_text()},
                                     db.path() + ".log"),
           db.path(), db.path() + ".log"};
  ASSERT_GT(s.p.port, 0) << read_file(s.log);

  // Every vessel with its position and its name (static data comes in its own message).
  std::set<std::uint32_t> expected;
  for (const auto& c : traffic.contacts())
    expected.insert(c.vessel.mmsi);
  json answer;
  const auto complete = [&] {
    std::set<std::uint32_t> named;
    for (const auto& c : answer["contacts"])
      if (!c["name"].get<std::string>().empty()) named.insert(c["mmsi"].get<std::uint32_t>());
    return named == expected;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  do {
    answer = s.traffic();
    if (complete()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } while (std::chrono::steady_clock::now() < deadline);
  ASSERT_TRUE(complete()) << answer.dump() << "\ngpsfake: " << gpsd.output();
  EXPECT_TRUE(answer["watching"].get<bool>());
  EXPECT_TRUE(answer["link_up"].get<bool>());
  EXPECT_EQ(answer["source"], "gpsd 127.0.0.1:" + gpsd.port_text());

  // On the station's grid: where the datum's plane puts the encoded position, to AIS's
  // quantisation (1/10000 minute: under 0.2 m).
  const avk::vehicle::LocalGrid grid(datum.lat_deg, datum.lon_deg);
  for (const auto& state : traffic.at(t_s)) {
    SCOPED_TRACE(state.vessel.mmsi);
    const auto c = std::find_if(answer["contacts"].begin(), answer["contacts"].end(),
                                [&](const json& j) { return j["mmsi"] == state.vessel.mmsi; });
    ASSERT_NE(c, answer["contacts"].end());
    const auto at = grid.to_grid(state.position);
    EXPECT_NEAR((*c)["x_m"].get<double>(), at.x_m, 0.5);
    EXPECT_NEAR((*c)["y_m"].get<double>(), at.y_m, 0.5);
    EXPECT_EQ((*c)["name"], state.vessel.name);
    EXPECT_NEAR((*c)["speed_mps"].get<double>(), state.speed_mps, 0.03);
    EXPECT_GE((*c)["age_s"].get<double>(), 0.0);
  }
}

TEST(TrafficApi, AStationWithoutASourceWatchesNothing) {
  avk::testing::TempDb db("avk_traffic_none");
  Served s{avk::testing::spawn_serve({"--db", db.path(), "--port", "0"}, db.path() + ".log"),
           db.path(), db.path() + ".log"};
  ASSERT_GT(s.p.port, 0) << read_file(s.log);
  const json t = s.traffic();
  EXPECT_FALSE(t["watching"].get<bool>());
  EXPECT_TRUE(t["source"].is_null());
  EXPECT_TRUE(t["contacts"].empty());
}

TEST(TrafficApi, AisNeedsADatumAndAHostAndPort) {
  avk::testing::TempDb db("avk_traffic_usage");
  const auto no_datum = avk::testing::run({"serve", "--db", db.path(), "--ais", "127.0.0.1:2947"});
  EXPECT_EQ(no_datum.rc, 2) << no_datum.err;
  EXPECT_NE(no_datum.err.find("--ais needs --datum"), std::string::npos) << no_datum.err;
  const auto no_port =
      avk::testing::run({"serve", "--db", db.path(), "--datum", "42.3,-71.1", "--ais", "gpsd"});
  EXPECT_EQ(no_port.rc, 2) << no_port.err;
  EXPECT_NE(no_port.err.find("HOST:PORT"), std::string::npos) << no_port.err;
  std::error_code ec;
  fs::remove(db.path() + ".token", ec);
}

}  // namespace
