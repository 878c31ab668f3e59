// The station's REST API for health, the vehicle and missions: the token, problems naming what is
// wrong, and a mission run, paused, resumed, aborted, and resumed by a new station after shutdown.
#include <gtest/gtest.h>

#include "server/station_api_fixture.hpp"

namespace {

using namespace avk::testing::station_api;

TEST_F(StationApi, HealthAndVehicle) {
  const json h = body(call(get("/api/v1/health")));
  EXPECT_EQ(h["status"], "ok");
  EXPECT_EQ(h["session_id"], hub_.session_id());
  EXPECT_EQ(h["vehicle_id"], "sim-usim");
  // The station clock beside the wall clock (for the dashboard's wall-clock times).
  const auto now_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                          std::chrono::system_clock::now().time_since_epoch())
                          .count();
  ASSERT_TRUE(h["utc_ms"].is_number_integer()) << h.dump();
  EXPECT_LE(h["utc_ms"].get<std::int64_t>(), now_ms);
  EXPECT_GT(h["utc_ms"].get<std::int64_t>(), now_ms - 600'000);  // taken during this test
  EXPECT_EQ(h["realtime_factor"], 400.0);
  ASSERT_TRUE(h["clock_s"].is_number() && h["session_start_clock_s"].is_number()) << h.dump();
  EXPECT_GE(h["clock_s"].get<double>(), h["session_start_clock_s"].get<double>());
  EXPECT_TRUE(h["datum"].is_null());
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
  // Before any mission the vehicle's motion is the defaults.
  const json motion = body(call(get("/api/v1/vehicles/sim-usim/motion")));
  EXPECT_EQ(motion["speed_reference"]["value"], "over_ground");
  EXPECT_EQ(motion["speed_reference"]["source"], "default");
  EXPECT_TRUE(motion["speed_reference"]["mission_id"].is_null());
  EXPECT_EQ(motion["drift_scatter"]["source"], "default");
  EXPECT_EQ(motion["drift_scatter"]["along_mps"], 0.10);
  EXPECT_TRUE(motion["current"].is_null());
  EXPECT_EQ(call(get("/api/v1/vehicles/nobody/motion")).status, 404);
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
    EXPECT_EQ(s.missions().get(id)->status, avk::store::MissionStatus::interrupted);
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

}  // namespace
