// A station for a fleet, end to end on a real server: three simulated vehicles (100x the wall
// clock) in one station and one database, each announced as it joins, each with its Foxglove
// channels, each running its own collection mission at the same time in its own region; every
// mission's track and turns are its own vehicle's, and each vehicle's table holds only its turns.
// Every wait is for a state, bounded; nothing measures time.
#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "server/http/http_server.hpp"
#include "server/station.hpp"
#include "support/http_client.hpp"
#include "support/sim_vehicle_loop.hpp"
#include "support/temp_db.hpp"
#include "support/ws_client.hpp"

namespace {

using avk::testing::http_call;
using avk::testing::WsClient;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr const char* kToken = "fleet-token-Vb8qN3zLw7XkP2mRt9YcJ5hD4sFg";

// Each vehicle's region is 200 m square about its own x offset; regions are 100 m apart.
const std::map<std::string, double> kOffsetM = {
    {"alpha", 0.0}, {"bravo", 300.0}, {"charlie", -300.0}};

std::string mission_for(double dx) {
  return json{
      {"name", "fleet"},
      {"turn_array", {{"speeds_mps", {0.5, 1.0}}, {"dheadings_deg", {40, 100}}, {"repeats", 1}}},
      {"operating_region",
       {{"polygon_m", {{dx - 100, -100}, {dx + 100, -100}, {dx + 100, 100}, {dx - 100, 100}}},
        {"buffer_m", 25},
        {"return_point_m", {dx, -70}}}}}
      .dump();
}

avk::server::StationOptions fleet_options(const std::string& db_path) {
  avk::server::StationOptions o;
  o.db_path = db_path;
  o.token = kToken;
  o.server_version = "test";
  for (const auto& [id, dx] : kOffsetM) {
    auto v = avk::testing::sim_usim_loop_options(100.0);
    v.setup.vehicle.id = id;
    v.start = {dx, -70.0, 0.0};
    o.vehicles.push_back(v);
  }
  return o;
}

std::map<std::string, std::string> control_headers() {
  return {{"Authorization", std::string("Bearer ") + kToken}, {"Content-Type", "application/json"}};
}

template <class Done>
bool wait_for(Done done, std::chrono::seconds limit = std::chrono::seconds(120)) {
  const auto deadline = Clock::now() + limit;
  while (!done()) {
    if (Clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return true;
}

TEST(FleetStation, ThreeVehiclesRunTheirOwnMissionsAtOnceInOneStation) {
  avk::testing::TempDb db("avk_fleet");
  avk::server::StreamHub hub;
  avk::server::Station station(fleet_options(db.path()), hub);
  avk::server::HttpServer server({}, station, hub);
  server.start();
  const unsigned short port = server.port();
  // Subscribed before the vehicles start, so every join is seen.
  WsClient ws(port);
  ASSERT_TRUE(ws.read().has_value());  // hello
  ws.send(R"({"subscribe":["status","nav","mission"]})");
  ASSERT_TRUE(ws.read().has_value());  // the acknowledgement
  station.start();

  std::set<std::string> joined, nav_from;
  const auto joins_deadline = Clock::now() + std::chrono::seconds(60);
  while ((joined.size() < 3 || nav_from.size() < 3) && Clock::now() < joins_deadline) {
    const auto m = ws.read(std::chrono::seconds(10));
    ASSERT_TRUE(m.has_value()) << "the stream went quiet";
    if (!m->contains("topic")) continue;
    const json& d = (*m)["data"];
    if ((*m)["topic"] == "status" && d["kind"] == "vehicle_joined") {
      ASSERT_TRUE(d.contains("vehicle_id")) << m->dump();
      const std::string vid = d["vehicle_id"];
      EXPECT_NE(d["message"].get<std::string>().find(vid), std::string::npos) << m->dump();
      joined.insert(vid);
    }
    if ((*m)["topic"] == "nav") nav_from.insert(d["vehicle_id"].get<std::string>());
  }
  const std::set<std::string> all = {"alpha", "bravo", "charlie"};
  EXPECT_EQ(joined, all);
  EXPECT_EQ(nav_from, all);

  const json health = json::parse(http_call(port, "GET", "/api/v1/health").body);
  EXPECT_EQ(health["vehicles"], json::array({"alpha", "bravo", "charlie"}));
  const json vehicles = json::parse(http_call(port, "GET", "/api/v1/vehicles").body);
  ASSERT_EQ(vehicles.size(), 3u);
  for (const auto& v : vehicles) {
    EXPECT_EQ(v["link"], "LIVE") << v.dump();
    // Each at its own start, 300 m from the next.
    EXPECT_NEAR(v["nav"]["x_m"].get<double>(), kOffsetM.at(v["id"]), 5.0) << v.dump();
  }

  // Foxglove: one connection advertises every vehicle's channels.
  {
    WsClient fox(port, "", 0, "/api/v1/foxglove", "foxglove.websocket.v1");
    ASSERT_FALSE(fox.handshake_error());
    std::set<std::string> topics;
    const auto fox_deadline = Clock::now() + std::chrono::seconds(20);
    while (Clock::now() < fox_deadline &&
           !(topics.contains("/alpha/pose") && topics.contains("/bravo/pose") &&
             topics.contains("/charlie/pose"))) {
      const auto m = fox.read(std::chrono::seconds(5));
      ASSERT_TRUE(m.has_value());
      if ((*m)["op"] == "advertise")
        for (const auto& c : (*m)["channels"])
          topics.insert(c["topic"].get<std::string>());
    }
    for (const auto& vid : all)
      for (const char* kind : {"pose", "navigation", "log"})
        EXPECT_TRUE(topics.contains("/" + vid + "/" + kind)) << vid << " " << kind;
  }

  // Three missions at once, one per vehicle.
  std::map<std::string, std::int64_t> mission_of;
  for (const auto& [vid, dx] : kOffsetM) {
    const auto r = http_call(port, "POST", "/api/v1/vehicles/" + vid + "/missions", mission_for(dx),
                             control_headers());
    ASSERT_EQ(r.status, 201) << vid << ": " << r.body;
    mission_of[vid] = json::parse(r.body)["id"].get<std::int64_t>();
  }
  bool all_running_at_once = false;
  const auto status_of = [&](std::int64_t id) {
    return json::parse(http_call(port, "GET", "/api/v1/missions/" + std::to_string(id)).body)
        .value("status", std::string());
  };
  ASSERT_TRUE(wait_for([&] {
    int running = 0, done = 0;
    for (const auto& [vid, id] : mission_of) {
      const std::string s = status_of(id);
      running += s == "running" || s == "created";
      done += s == "done";
      EXPECT_TRUE(s != "halted" && s != "aborted") << vid << " mission " << id << " " << s;
    }
    if (running == 3) all_running_at_once = true;
    return done == 3;
  })) << "not every mission finished";
  EXPECT_TRUE(all_running_at_once);

  for (const auto& [vid, id] : mission_of) {
    const json report =
        json::parse(http_call(port, "GET", "/api/v1/missions/" + std::to_string(id)).body);
    EXPECT_EQ(report["vehicle_id"], vid);
    ASSERT_FALSE(report["turn_list"].empty()) << vid;
    for (const auto& t : report["turn_list"])
      EXPECT_EQ(t["vehicle_id"], vid);
    // The recorded track is this vehicle's: inside its own region (with its buffer and some
    // overshoot), never in a neighbour's, which begins 100 m away.
    const json track = json::parse(
        http_call(port, "GET", "/api/v1/missions/" + std::to_string(id) + "/nav?limit=10000").body);
    ASSERT_FALSE(track["items"].empty());
    for (const auto& p : track["items"]) {
      const double x = p["x_m"].get<double>();
      ASSERT_LT(std::abs(x - kOffsetM.at(vid)), 150.0) << vid << " at x " << x;
    }
    // The vehicle's table is built from its own turns only: as many as its mission's ok turns.
    int ok_turns = 0;
    for (const auto& t : report["turn_list"])
      ok_turns += t["status"] == "ok";
    const json ckt = json::parse(http_call(port, "GET", "/api/v1/vehicles/" + vid + "/ckt").body);
    int in_table = 0;
    for (const auto& c : ckt["cells"])
      in_table += c["n_turns"].get<int>();
    EXPECT_GT(ok_turns, 0) << vid;
    EXPECT_EQ(in_table, ok_turns) << vid << ": " << ckt.dump();
  }
  station.shutdown();
  server.stop();
}

TEST(FleetStation, TheOtherVehiclesAreLiveContactsOfAManeuverEvaluation) {
  avk::testing::TempDb db("avk_fleet_contacts");
  avk::server::StreamHub hub;
  avk::server::Station station(fleet_options(db.path()), hub);
  avk::server::HttpServer server({}, station, hub);
  server.start();
  station.start();
  const unsigned short port = server.port();
  ASSERT_TRUE(wait_for([&] {
    const json v = json::parse(http_call(port, "GET", "/api/v1/vehicles").body);
    int with_nav = 0;
    for (const auto& x : v)
      with_nav += x["nav"].is_object();
    return with_nav == 3;
  }));
  const json body = {
      {"own", {{"x_m", 0.0}, {"y_m", -70.0}, {"heading_deg", 90.0}, {"speed_mps", 1.0}}},
      {"live_contacts", true},
      {"method", "instantaneous"},
      {"candidates_deg", {0, 90}},
      {"standoff_m", 20.0},
      {"horizon_s", 400.0}};
  const auto r = http_call(port, "POST", "/api/v1/vehicles/alpha/maneuvers/evaluate", body.dump(),
                           control_headers());
  ASSERT_EQ(r.status, 200) << r.body;
  const json e = json::parse(r.body);
  // Every vehicle but alpha itself, where the station has it.
  EXPECT_EQ(e["live_contacts"], json::array({"bravo", "charlie"}));
  ASSERT_EQ(e["contacts"].size(), 2u);
  EXPECT_NEAR(e["contacts"][0]["x_m"].get<double>(), 300.0, 5.0);
  EXPECT_NEAR(e["contacts"][1]["x_m"].get<double>(), -300.0, 5.0);
  // Heading east at bravo, which sits at rest 300 m ahead: straight on (0) meets it, 90 does not.
  ASSERT_EQ(e["candidates"].size(), 2u);
  EXPECT_LT(e["candidates"][0]["min_cpa_m"].get<double>(), 20.0);
  EXPECT_GT(e["candidates"][1]["min_cpa_m"].get<double>(), 20.0);
  station.shutdown();
  server.stop();
}

}  // namespace
