// The station's REST handlers over a real store and a real simulated vehicle (paced fast), called
// without sockets: every endpoint and every error path of the REST API.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "kinematics/ckt_file.hpp"
#include "server/station.hpp"
#include "sim/sim_config.hpp"
#include "store/store.hpp"
#include "support/sim_station.hpp"
#include "support/temp_db.hpp"

using avk::server::ApiRequest;
using avk::server::ApiResponse;
using avk::server::Station;
using avk::server::StreamHub;
using nlohmann::json;

namespace {

constexpr const char* kToken = "test-token";

// Four turns of the Figure 4-1 kind on a wide region.
std::string small_mission(double speed2 = 1.0) {
  return json{
      {"name", "api-test"},
      {"turn_array", {{"speeds_mps", {0.5, speed2}}, {"dheadings_deg", {40, 100}}, {"repeats", 1}}},
      {"operating_region",
       {{"polygon_m", {{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}},
        {"buffer_m", 25},
        {"return_point_m", {0, -70}}}}}
      .dump();
}

ApiRequest get(const std::string& path, std::map<std::string, std::string> query = {}) {
  ApiRequest r;
  r.method = "GET";
  r.path = path;
  for (const auto& [k, v] : query)
    r.multi_query.emplace(k, v);
  r.query = std::move(query);
  return r;
}

ApiRequest post(const std::string& path, const std::string& body = "{}",
                const std::string& token = kToken) {
  ApiRequest r;
  r.method = "POST";
  r.path = path;
  r.body = body;
  r.content_type = "application/json";
  if (!token.empty()) r.authorization = "Bearer " + token;
  return r;
}

json body(const ApiResponse& r) {
  return json::parse(r.body);
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

TEST_F(StationApi, HealthAndVehicle) {
  const json h = body(call(get("/api/v1/health")));
  EXPECT_EQ(h["status"], "ok");
  EXPECT_EQ(h["session_id"], hub_.session_id());
  EXPECT_EQ(h["vehicle_id"], "sim-usim");
  // The simulated vehicle runs from the start: navigation arrives and the link goes live.
  json v;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    v = body(call(get("/api/v1/vehicles/sim-usim")));
    if (v["link"] == "LIVE") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(v["link"], "LIVE");
  EXPECT_TRUE(v["nav"].is_object());
  EXPECT_TRUE(v["helm_mode"].is_null()) << v.dump();  // no mission drives the helm
  EXPECT_EQ(call(get("/api/v1/vehicles/nobody")).status, 404);
  EXPECT_EQ(body(call(get("/api/v1/vehicles"))).size(), 1u);
}

TEST_F(StationApi, ControlNeedsTheTokenAndReadsFromAfarToo) {
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/missions", small_mission(), "")).status, 401);
  const ApiResponse wrong = call(post("/api/v1/vehicles/sim-usim/missions", small_mission(), "x"));
  EXPECT_EQ(wrong.status, 401);
  EXPECT_EQ(wrong.content_type, "application/problem+json");
  ApiRequest remote = get("/api/v1/health");
  remote.remote_is_loopback = false;
  EXPECT_EQ(call(remote).status, 401);
  remote.authorization = std::string("Bearer ") + kToken;
  EXPECT_EQ(call(remote).status, 200);
  // Nothing was created by the refused requests.
  EXPECT_TRUE(body(call(get("/api/v1/missions"))).empty());
}

TEST_F(StationApi, BadRequestsAreProblemsNamingWhatIsWrong) {
  ApiRequest text = post("/api/v1/vehicles/sim-usim/missions", small_mission());
  text.content_type = "text/plain";
  EXPECT_EQ(call(text).status, 415);
  const ApiResponse invalid =
      call(post("/api/v1/vehicles/sim-usim/missions", R"({"name":"x","turn_array":{}})"));
  EXPECT_EQ(invalid.status, 422);
  const json p = body(invalid);
  EXPECT_EQ(p["status"], 422);
  ASSERT_TRUE(p["errors"].is_array());
  bool names_speeds = false;
  for (const auto& e : p["errors"])
    names_speeds |= e["field"] == "/turn_array/speeds_mps";
  EXPECT_TRUE(names_speeds) << p.dump();
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/missions", "{not json")).status, 422);
  EXPECT_EQ(call(post("/api/v1/health")).status, 405);
  EXPECT_EQ(call(get("/api/v1/nothing/here")).status, 404);
  EXPECT_EQ(call(get("/api/v1/missions/abc")).status, 404);
  EXPECT_EQ(call(get("/api/v1/missions/42")).status, 404);
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"limit", "abc"},
                                                        {"limit", "nan"},
                                                        {"limit", "0"},
                                                        {"speed", "1e999"},
                                                        {"after", "-3"},
                                                        {"status", "great"}}) {
    const ApiResponse r = call(get("/api/v1/turns", {{name, value}}));
    EXPECT_EQ(r.status, 400) << name << "=" << value;
    EXPECT_NE(body(r)["detail"].get<std::string>().find(name), std::string::npos) << r.body;
  }
  ApiRequest png = get("/api/v1/turns");
  png.accept = "image/png";
  EXPECT_EQ(call(png).status, 406);
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict", {{"speed", "1"}})).status, 400);
}

TEST_F(StationApi, MissionRunsPausesResumesAndEveryTurnIsServed) {
  const std::int64_t id = start_mission();
  // Another mission while this one runs: 409.
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/missions", small_mission())).status, 409);
  json m = body(call(get("/api/v1/missions/" + std::to_string(id))));
  EXPECT_EQ(m["cells"].size(), 4u);
  const ApiResponse paused = call(post("/api/v1/missions/" + std::to_string(id) + "/pause"));
  EXPECT_EQ(paused.status, 200) << paused.body;
  EXPECT_EQ(wait_for(id, {"paused"})["status"], "paused");
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim")))["helm_mode"], "PAUSED");
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/resume")).status, 200);
  m = wait_for(id, {"done", "halted", "aborted"});
  EXPECT_EQ(m["status"], "done") << m.dump();
  // Every turn the mission finished is in /turns and in the table.
  const json turns =
      body(call(get("/api/v1/turns", {{"mission", std::to_string(id)}, {"status", "ok"}})));
  EXPECT_EQ(turns["items"].size(), 4u) << turns.dump();
  const json ckt = body(call(get("/api/v1/vehicles/sim-usim/ckt")));
  int n = 0;
  for (const auto& c : ckt["cells"])
    n += c["n_turns"].get<int>();
  EXPECT_EQ(n, 4);
  // Control of a finished mission is a conflict.
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/pause")).status, 409);
}

// Pause is one step across mission and helm: whoever reads the mission as paused reads the
// vehicle's helm as PAUSED too. The vehicle's telemetry refreshes only every 20 s of mission
// clock here (a second of wall time), so a helm mode that waited for it would show the mode from
// before the pause; the helm's own update must carry it.
TEST_F(StationApi, APausedMissionIsNeverShownWithAHelmThatIsNotPaused) {
  station_.reset();
  start(20.0, 0.05);
  const std::int64_t id = start_mission();
  const std::string mission_path = "/api/v1/missions/" + std::to_string(id);
  // Wait until the helm has taken the mission up (the vehicle names it).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  json v;
  while (std::chrono::steady_clock::now() < deadline) {
    v = body(call(get("/api/v1/vehicles/sim-usim")));
    if (v["mission_id"] == id) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_EQ(v["mission_id"], id) << v.dump();
  const ApiResponse paused = call(post(mission_path + "/pause"));
  ASSERT_EQ(paused.status, 200) << paused.body;
  // The answer may come before the helm tick applied the pause (under load); if it says paused,
  // its helm says so too.
  const json answer = body(paused);
  if (answer["status"] == "paused") {
    EXPECT_EQ(answer["helm_mode"], "PAUSED") << paused.body;
  }
  const json m = wait_for(id, {"paused"});
  EXPECT_EQ(m["helm_mode"], "PAUSED") << m.dump();
  v = body(call(get("/api/v1/vehicles/sim-usim")));
  EXPECT_EQ(v["helm_mode"], "PAUSED") << v.dump();
  EXPECT_EQ(v["mission_id"], id);
  EXPECT_TRUE(v["desired_speed_mps"].is_null()) << v.dump();  // all stop
  // The mission list reads the store, which records the pause after the helm has it.
  const json list = body(call(get("/api/v1/missions")));
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["status"], "paused");
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim")))["helm_mode"], "PAUSED");
  EXPECT_EQ(call(post(mission_path + "/abort")).status, 200);
  EXPECT_EQ(wait_for(id, {"aborted"})["status"], "aborted");
}

TEST_F(StationApi, AbortStopsTheVehicle) {
  const std::int64_t id = start_mission();
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/abort")).status, 200);
  EXPECT_EQ(wait_for(id, {"aborted"})["status"], "aborted");
  // The next mission may start.
  const std::int64_t next = start_mission();
  EXPECT_GT(next, id);
}

TEST_F(StationApi, ShutdownInterruptsAndANewStationResumes) {
  const std::int64_t id = start_mission();
  // Let it record at least one turn, then stop the station as SIGTERM would.
  for (int i = 0; i < 3000; ++i) {
    if (!body(call(get("/api/v1/turns", {{"mission", std::to_string(id)}})))["items"].empty())
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  station_->shutdown();
  {
    avk::store::Store s(db_.path());
    EXPECT_EQ(s.get_mission(id)->status, avk::store::MissionStatus::interrupted);
    EXPECT_TRUE(s.integrity_check());
  }
  station_.reset();
  start();
  EXPECT_EQ(body(call(get("/api/v1/missions/" + std::to_string(id))))["status"], "interrupted");
  EXPECT_EQ(call(post("/api/v1/missions/" + std::to_string(id) + "/resume")).status, 200);
  EXPECT_EQ(wait_for(id, {"done", "halted"})["status"], "done");
  const json ok =
      body(call(get("/api/v1/turns", {{"mission", std::to_string(id)}, {"status", "ok"}})));
  EXPECT_EQ(ok["items"].size(), 4u);
}

TEST_F(StationApi, TurnsPageByKeysetAndComeAsCsv) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const json first = body(call(get("/api/v1/turns", {{"limit", "2"}})));
  ASSERT_EQ(first["items"].size(), 2u);
  ASSERT_TRUE(first["next"].is_number());
  const json second =
      body(call(get("/api/v1/turns", {{"limit", "2"}, {"after", first["next"].dump()}})));
  ASSERT_FALSE(second["items"].empty());
  EXPECT_GT(second["items"][0]["id"].get<int>(), first["items"][1]["id"].get<int>());
  ApiRequest csv = get("/api/v1/turns");
  csv.accept = "text/csv";
  const ApiResponse c = call(csv);
  EXPECT_EQ(c.status, 200);
  EXPECT_EQ(c.content_type.rfind("text/csv", 0), 0u);
  EXPECT_EQ(c.body.rfind("id,mission_id,vehicle_id,status,reason,speed_mps,goal_dheading_deg", 0),
            0u);
  EXPECT_NE(c.body.find("advance_m"), std::string::npos);
  const auto tid = first["items"][0]["id"].get<std::int64_t>();
  const json t = body(call(get("/api/v1/turns/" + std::to_string(tid))));
  // The raw and normalised records of the same turn: same samples count, the normalised one
  // starting at the origin.
  ASSERT_TRUE(t["raw"]["samples"].is_array());
  ASSERT_TRUE(t["normalized"]["samples"].is_array());
  EXPECT_GT(t["raw"]["samples"].size(), 3u);
  EXPECT_EQ(t["raw"]["samples"].size(), t["normalized"]["samples"].size());
  EXPECT_EQ(t["normalized"]["normalized"], true);
  EXPECT_DOUBLE_EQ(t["normalized"]["samples"][0][1].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(t["normalized"]["samples"][0][2].get<double>(), 0.0);
  EXPECT_TRUE(t["normalized"].is_object());
  EXPECT_EQ(call(get("/api/v1/turns/999999")).status, 404);
}

TEST_F(StationApi, CktCellsExportImportPredictModelsCompare) {
  wait_for(start_mission(), {"done"});
  wait_for(start_mission(), {"done"});  // two turns a cell for the comparison
  const json cell = body(
      call(get("/api/v1/vehicles/sim-usim/ckt/cells", {{"speed", "0.5"}, {"dheading", "100"}})));
  EXPECT_EQ(cell["n_turns"], 2);
  EXPECT_EQ(cell["turns"].size(), 2u);
  EXPECT_FALSE(cell["mean"].empty());
  EXPECT_FALSE(cell["trajectory"].empty());
  EXPECT_EQ(
      call(get("/api/v1/vehicles/sim-usim/ckt/cells", {{"speed", "0.7"}, {"dheading", "100"}}))
          .status,
      404);
  const ApiResponse exported =
      call(get("/api/v1/vehicles/sim-usim/ckt/export", {{"format", "json"}}));
  ASSERT_EQ(exported.status, 200);
  bool disposition = false;
  for (const auto& [k, v] : exported.headers)
    disposition |= k == "Content-Disposition";
  EXPECT_TRUE(disposition);
  EXPECT_NO_THROW(avk::kinematics::parse_ckt_json(exported.body));
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/ckt/import", exported.body)).status, 201);
  EXPECT_EQ(call(post("/api/v1/vehicles/other/ckt/import", exported.body)).status, 422);
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/ckt/import", R"({"schema":99})")).status, 422);

  const json avk = body(call(
      get("/api/v1/vehicles/sim-usim/predict",
          {{"speed", "0.75"}, {"dheading", "-70"}, {"x", "10"}, {"y", "5"}, {"heading", "90"}})));
  EXPECT_EQ(avk["frame"], "world");
  EXPECT_DOUBLE_EQ(avk["trajectory"][0][0].get<double>(), 10.0);
  EXPECT_EQ(
      call(get("/api/v1/vehicles/sim-usim/predict", {{"speed", "3"}, {"dheading", "70"}})).status,
      400);  // outside the table's speeds
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict",
                     {{"speed", "1"}, {"dheading", "70"}, {"method", "model"}}))
                .status,
            404);  // no model yet
  const json missions = body(call(get("/api/v1/missions")));
  const ApiResponse fitted = call(
      post("/api/v1/vehicles/sim-usim/models",
           json{{"missions", {missions[0]["id"], missions[1]["id"]}}, {"history_s", 3}}.dump()));
  ASSERT_EQ(fitted.status, 201) << fitted.body;
  const auto model_id = body(fitted)["id"].get<std::int64_t>();
  EXPECT_EQ(body(call(get("/api/v1/models/" + std::to_string(model_id))))["history"], 12);
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/models"))).size(), 1u);
  EXPECT_EQ(call(post("/api/v1/vehicles/sim-usim/models", R"({"missions":[999]})")).status, 422);
  const json model = body(call(get("/api/v1/vehicles/sim-usim/predict",
                                   {{"speed", "1"}, {"dheading", "70"}, {"method", "model"}})));
  EXPECT_EQ(model["model_id"], model_id);
  // Issue 17 part 2: the speed after is a parameter named in its error; equal to the speed it is
  // a constant-speed turn; the model flies a change with its speed model (or says it has none).
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict",
                     {{"speed", "1"}, {"dheading", "70"}, {"speed_after", "-1"}}))
                .status,
            400);
  const json same = body(call(get("/api/v1/vehicles/sim-usim/predict",
                                  {{"speed", "1"}, {"dheading", "70"}, {"speed_after", "1"}})));
  EXPECT_FALSE(same.contains("speed_change_source"));
  const ApiResponse slowing =
      call(get("/api/v1/vehicles/sim-usim/predict",
               {{"speed", "1"}, {"dheading", "70"}, {"speed_after", "0.5"}, {"method", "model"}}));
  if (slowing.status == 200) {
    EXPECT_EQ(body(slowing)["speed_change_source"], "model");
    EXPECT_EQ(body(slowing)["speed_after_mps"], 0.5);
  } else {
    EXPECT_EQ(slowing.status, 400) << slowing.body;
    EXPECT_NE(slowing.body.find("speed_after"), std::string::npos) << slowing.body;
  }
  const json comparison = body(call(get("/api/v1/vehicles/sim-usim/compare")));
  EXPECT_EQ(comparison["cells"].size(), 4u);
  EXPECT_EQ(comparison["model_id"], model_id);
  ApiRequest csv = get("/api/v1/vehicles/sim-usim/compare", {{"format", "csv"}});
  EXPECT_EQ(call(csv).body.rfind("speed_mps,dheading_deg,n_turns", 0), 0u);
}

TEST_F(StationApi, NavPagesConcatenateToTheStoredTrack) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const auto stored = avk::store::Store(db_.path()).nav_for_mission(id);
  ASSERT_GT(stored.size(), 1000u);
  const std::string path = "/api/v1/missions/" + std::to_string(id) + "/nav";
  std::vector<json> rows;
  std::map<std::string, std::string> q = {{"limit", "400"}};
  int pages = 0;
  for (;;) {
    const ApiResponse r = call(get(path, q));
    ASSERT_EQ(r.status, 200) << r.body;
    const json page = body(r);
    ++pages;
    ASSERT_LE(page["items"].size(), 400u);
    for (const auto& item : page["items"])
      rows.push_back(item);
    if (page["next"].is_null()) break;
    q["after"] = page["next"].dump();
  }
  EXPECT_EQ(pages, static_cast<int>(stored.size() / 400 + 1));
  ASSERT_EQ(rows.size(), stored.size());
  // Insertion order is the recorder's time order for one run: the same rows as nav_for_mission.
  for (std::size_t i = 0; i < rows.size(); i += 97) {
    EXPECT_EQ(rows[i]["t_s"].get<double>(), stored[i].t_s);
    EXPECT_EQ(rows[i]["x_m"].get<double>(), stored[i].x_m);
    EXPECT_EQ(rows[i]["helm_mode"].get<std::string>(), stored[i].helm_mode);
    for (const char* k :
         {"y_m", "heading_deg", "speed_mps", "desired_heading_deg", "desired_speed_mps"})
      EXPECT_TRUE(rows[i].contains(k)) << k;
  }
  // The default page is 5000 rows.
  EXPECT_EQ(body(call(get(path)))["items"].size(), std::min<std::size_t>(stored.size(), 5000));
  EXPECT_EQ(call(get("/api/v1/missions/999/nav")).status, 404);
  for (const auto& [k, v] : std::vector<std::pair<std::string, std::string>>{
           {"limit", "0"}, {"limit", "10001"}, {"limit", "2.5"}, {"after", "-1"}, {"after", "x"}}) {
    const ApiResponse bad = call(get(path, {{k, v}}));
    EXPECT_EQ(bad.status, 400) << k << "=" << v;
    EXPECT_EQ(body(bad)["parameter"], k);
  }
}

TEST_F(StationApi, ModelHeadingsOneStepAndSimulated) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const ApiResponse fitted = call(
      post("/api/v1/vehicles/sim-usim/models", json{{"missions", {id}}, {"history_s", 3}}.dump()));
  ASSERT_EQ(fitted.status, 201) << fitted.body;
  const auto model_id = body(fitted)["id"].get<std::int64_t>();
  const std::string path = "/api/v1/models/" + std::to_string(model_id) + "/headings";
  const ApiResponse r = call(get(path, {{"mission", std::to_string(id)}}));
  ASSERT_EQ(r.status, 200) << r.body;
  const json h = body(r);
  EXPECT_DOUBLE_EQ(h["dt_s"].get<double>(), 0.25);
  const std::size_t warmup = 13;  // 3 s at 4 Hz, + 1 for the invariant form's increments
  EXPECT_EQ(h["warmup_samples"], warmup);
  ASSERT_FALSE(h["segments"].empty());
  std::size_t total = 0, compared = 0;
  double one_sq = 0.0, sim_sq = 0.0;
  for (const auto& s : h["segments"]) {
    const std::size_t n = s["heading_deg"].size();
    total += n;
    for (const char* k : {"desired_heading_deg", "one_step_deg", "simulated_deg"})
      ASSERT_EQ(s[k].size(), n) << k;
    for (std::size_t k = 0; k < n; ++k) {
      if (k < warmup) {
        EXPECT_TRUE(s["one_step_deg"][k].is_null()) << k;
        EXPECT_TRUE(s["simulated_deg"][k].is_null()) << k;
        continue;
      }
      ASSERT_TRUE(s["one_step_deg"][k].is_number()) << k;
      ASSERT_TRUE(s["simulated_deg"][k].is_number()) << k;
      const double measured = s["heading_deg"][k].get<double>();
      one_sq += std::pow(s["one_step_deg"][k].get<double>() - measured, 2);
      sim_sq += std::pow(s["simulated_deg"][k].get<double>() - measured, 2);
      ++compared;
    }
  }
  EXPECT_LE(total, 2400u);
  ASSERT_GT(compared, 100u);
  // One step from measured history is the easier problem: it must be closer on average.
  EXPECT_LT(one_sq, sim_sq);
  EXPECT_LT(std::sqrt(one_sq / compared), 2.0);

  const json capped = body(call(get(path, {{"mission", std::to_string(id)}, {"limit", "50"}})));
  std::size_t capped_total = 0;
  for (const auto& s : capped["segments"])
    capped_total += s["heading_deg"].size();
  EXPECT_EQ(capped_total, std::min<std::size_t>(total, 50));
  EXPECT_EQ(capped["segments"][0]["heading_deg"],
            json(std::vector<double>(h["segments"][0]["heading_deg"].begin(),
                                     h["segments"][0]["heading_deg"].begin() +
                                         static_cast<long>(std::min<std::size_t>(
                                             50, h["segments"][0]["heading_deg"].size())))));

  EXPECT_EQ(call(get("/api/v1/models/999/headings", {{"mission", std::to_string(id)}})).status,
            404);
  EXPECT_EQ(call(get(path, {{"mission", "999"}})).status, 404);
  EXPECT_EQ(call(get(path)).status, 400);
  EXPECT_EQ(call(get(path, {{"mission", std::to_string(id)}, {"limit", "0"}})).status, 400);
  std::int64_t empty = 0;
  {
    avk::store::Store s(db_.path());
    empty = s.create_mission("sim-usim", "no nav", "{}");
  }
  const ApiResponse none = call(get(path, {{"mission", std::to_string(empty)}}));
  EXPECT_EQ(none.status, 422) << none.body;
}

// Issue 17 part 4: harvesting is a write (the token always), and its counts come back; the CKT
// endpoints take include=collection|harvested.
TEST_F(StationApi, HarvestIsAControlEndpointAndTheTableSaysWhatItIncludes) {
  const std::int64_t id = start_mission();
  wait_for(id, {"done"});
  const std::string path = "/api/v1/missions/" + std::to_string(id) + "/harvest";
  EXPECT_EQ(call(post(path, "", "")).status, 401);
  const ApiResponse r = call(post(path, ""));
  ASSERT_EQ(r.status, 200) << r.body;
  const json h = body(r);
  EXPECT_EQ(h["mission_id"], id);
  EXPECT_GE(h["already_recorded"].get<int>(), 4);  // the mission's own turns, not twice
  EXPECT_EQ(h["steps"].get<int>(), h["harvested"].get<int>() + h["already_recorded"].get<int>() +
                                       h["rejected"].get<int>());
  EXPECT_EQ(h["rejected_by_reason"].size(), 13u);
  EXPECT_EQ(call(post("/api/v1/missions/999/harvest", "")).status, 404);
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/ckt")))["include"], "collection");
  EXPECT_EQ(body(call(get("/api/v1/vehicles/sim-usim/ckt", {{"include", "harvested"}})))["include"],
            "harvested");
  const ApiResponse bad = call(get("/api/v1/vehicles/sim-usim/ckt", {{"include", "all"}}));
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("include"), std::string::npos);
  EXPECT_EQ(call(get("/api/v1/vehicles/sim-usim/predict",
                     {{"speed", "0.5"}, {"dheading", "40"}, {"include", "harvested"}}))
                .status,
            200);
}

}  // namespace
