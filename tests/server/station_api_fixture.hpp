#pragma once
// The station's REST handlers called without sockets: requests and answers as a client writes and
// reads them, docs/api.md as a client reads it, and a station over a real store and a simulated
// vehicle (paced fast).

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "kinematics/ckt_file.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"
#include "store/store.hpp"
#include "support/sim_station.hpp"
#include "support/temp_db.hpp"

namespace avk::testing::station_api {

using avk::server::ApiRequest;
using avk::server::ApiResponse;
using avk::server::Station;
using avk::server::StreamHub;
using nlohmann::json;

inline constexpr const char* kToken = "test-token";

// Four turns of the Figure 4-1 kind on a wide region.
inline std::string small_mission(double speed2 = 1.0) {
  return json{
      {"name", "api-test"},
      {"turn_array", {{"speeds_mps", {0.5, speed2}}, {"dheadings_deg", {40, 100}}, {"repeats", 1}}},
      {"operating_region",
       {{"polygon_m", {{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}},
        {"buffer_m", 25},
        {"return_point_m", {0, -70}}}}}
      .dump();
}

inline ApiRequest get(const std::string& path, std::map<std::string, std::string> query = {}) {
  ApiRequest r;
  r.method = "GET";
  r.path = path;
  for (const auto& [k, v] : query)
    r.multi_query.emplace(k, v);
  r.query = std::move(query);
  return r;
}

inline ApiRequest post(const std::string& path, const std::string& body = "{}",
                       const std::string& token = kToken) {
  ApiRequest r;
  r.method = "POST";
  r.path = path;
  r.body = body;
  r.content_type = "application/json";
  if (!token.empty()) r.authorization = "Bearer " + token;
  return r;
}

inline json body(const ApiResponse& r) {
  return json::parse(r.body);
}

inline std::string header(const ApiResponse& r, const std::string& name) {
  for (const auto& [k, v] : r.headers)
    if (k == name) return v;
  return "";
}

// --- docs/api.md, read as a client reads it ----------------------------------------------

inline std::string api_doc() {
  std::ifstream f(std::string(AVK_SOURCE_DIR) + "/docs/api.md");
  std::stringstream text;
  text << f.rdbuf();
  return text.str();
}

class StationApi : public ::testing::Test {
 protected:
  void SetUp() override { start(); }
  void TearDown() override { station_.reset(); }

  // telemetry_hz: how often the vehicle's snapshot is refreshed besides the helm's own updates.
  void start(double realtime_factor = 400.0, double telemetry_hz = 10.0) {
    station_ = std::make_unique<Station>(
        avk::testing::sim_station_options(db_.path(), kToken, realtime_factor, telemetry_hz), hub_);
    station_->start();
  }

  ApiResponse call(const ApiRequest& r) { return station_->handle(r); }

  // Polls the mission until its status is one of `states` (bounded: 60 s).
  json wait_for(std::int64_t id, const std::set<std::string>& states) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    json m;
    while (std::chrono::steady_clock::now() < deadline) {
      m = body(call(get("/api/v1/missions/" + std::to_string(id))));
      if (states.count(m["status"].get<std::string>())) return m;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ADD_FAILURE() << "mission " << id << " stayed " << m["status"];
    return m;
  }

  std::int64_t start_mission(const std::string& config = small_mission()) {
    const ApiResponse r = call(post("/api/v1/vehicles/sim-usim/missions", config));
    EXPECT_EQ(r.status, 201) << r.body;
    return body(r)["id"].get<std::int64_t>();
  }

  avk::testing::TempDb db_{"avk_station_api"};
  StreamHub hub_;
  std::unique_ptr<Station> station_;
};

}  // namespace avk::testing::station_api
